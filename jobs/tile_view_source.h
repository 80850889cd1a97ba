#pragma once
// The views of one tile: of each view that sees the tile's halo box, only the window of its depth map, colour
// cache and superpixel labels that the box needs (tiles/tile_plan.h). The superpixel and colour caches must exist
// (EnsureTiledSuperpixels, jobs/tile_fusion.h). A cluster whose centroid lies in the window becomes the same node
// as in an untiled run: cluster statistics are the whole view's (from the cache file's table).
#include <string>

#include "jobs/cluster_table_cache.h"
#include "tiles/tile_plan.h"
#include "jobs/view_source.h"

namespace sacfuse {

class TileViewSource : public ViewSource {
 public:
  // `cluster_cache` (may be null) shares the views' cluster tables between the tiles of a run.
  TileViewSource(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile, std::string cache_dir,
                 ClusterTableCache* cluster_cache = nullptr);
  std::unique_ptr<LoadedViews> Load(const FusionNeeds& needs) const override;
  RgbImage LoadColours(const LoadedViews& loaded, size_t i) const override;

 private:
  const DepthBlock& input_;
  const TilePlan& plan_;
  const PlannedTile& tile_;
  std::string cache_dir_;
  ClusterTableCache* cluster_cache_;
};

}  // namespace sacfuse
