#pragma once
// Where a fusion run's views come from: the one seam between the job (which decides what is in memory) and a
// fusion method (core/fusion_method.h). Two sources, like COLMAP's Workspace / CachedWorkspace:
//   jobs/block_view_source.h  the whole block (an untiled run): whole depth maps
//   jobs/tile_view_source.h   one tile: only the windows of its views that its halo box needs
// Both give the method the same rasters for the same pixels: depth, colours resampled to the depth grid (the
// colour cache's content), the superpixels of the view's cache file, so a pixel's way to a point depends on
// its tile only through the halo context.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/consistency_graph.h"
#include "core/fusion_method.h"
#include "core/raster.h"
#include "core/sac_view.h"
#include "io/depth_block.h"

namespace sacfuse {

// The rasters one run holds and the views pointing into them.
struct LoadedViews {
  std::vector<SacView> views;      // what the method reads
  std::vector<uint32_t> view_ids;  // the block's index of each view (DepthBlock::views())
  size_t superpixels_computed = 0; // views whose superpixels were computed while loading (not from the cache)
  double load_seconds = 0.0;       // reading (and computing superpixels), wall time

  // Storage the views point into: sized once (Reserve) before any view points into it.
  std::vector<DepthMap> depths;
  std::vector<SuperpixelMap> superpixels;
  // Depth-grid resolution; empty = the view has no image (grey points), or its colours are loaded when the method
  // asks (FusionNeeds::colours_one_view_at_a_time, ViewSource::LoadColours).
  std::vector<RgbImage> colours;
  std::vector<ConsistencyGraph> graphs;

  void Reserve(size_t n) {
    depths.resize(n);
    superpixels.resize(n);
    colours.resize(n);
    graphs.resize(n);
  }
  // Appends view i of the storage: `view` cut to `window` of its depth raster of size `raster`.
  void AddView(uint32_t view_id, const View& view, const DepthRasterSize& raster, const PixelWindow& window,
               const FusionNeeds& needs, size_t i);
  LoadedViews() = default;
  LoadedViews(const LoadedViews&) = delete;
  LoadedViews& operator=(const LoadedViews&) = delete;
};

class ViewSource {
 public:
  virtual ~ViewSource() = default;
  // Loads the views of the run with what `needs` asks for. Throws InputError / Error on unreadable inputs.
  virtual std::unique_ptr<LoadedViews> Load(const FusionNeeds& needs) const = 0;
  // The colours of view i of `loaded` (which this source's Load returned) on its depth grid or window: what Load
  // puts in LoadedViews::colours unless needs.colours_one_view_at_a_time. Throws InputError.
  virtual RgbImage LoadColours(const LoadedViews& loaded, size_t i) const = 0;
};

}  // namespace sacfuse
