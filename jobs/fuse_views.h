#pragma once
// The one way every fusion method runs, whole block or tile: load the views (jobs/view_source.h), give the
// method its scope (the block's neighbour plan restricted to the loaded views, the GSD, the tile's halo box and
// core), fuse into the sink, count. A tile's points outside its core are left to the neighbouring tiles: SAC
// judges each pixel on its own point (FusionNeeds::owns_pixels), the other methods' emitted points are judged here.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/fusion_method.h"
#include "core/point.h"
#include "jobs/method_geometry.h"
#include "jobs/view_source.h"

namespace sacfuse {

struct FusedViews {
  // Per-view vectors indexed like view_ids; input counts only the valid pixels whose own point the scope owns.
  FusionStats stats;
  std::vector<uint32_t> view_ids;      // the block's index of each loaded view
  uint64_t points_written = 0;         // to the sink
  std::vector<uint64_t> points_per_view;  // written to the sink, by the block's view index (FusedPoint::view_index)
  uint64_t points_not_owned = 0;       // left to other tiles (SAC: valid pixels; others: emitted points)
  size_t superpixels_computed = 0;     // while loading (whole-block runs)
  double load_seconds = 0.0;
};

// `geometry`: the block's (jobs/method_geometry.h), needed by methods with FusionNeeds::block_geometry.
// `scope.plan` and `scope.gsd_m` are filled here. `loaded` (optional) is called once the views are loaded, before
// the method runs (an untiled run's stage clock, jobs/run_fusion.h).
FusedViews FuseViews(const FusionMethod& method, const ViewSource& source, const MethodGeometry* geometry,
                     FusionScope scope, PointSink& sink, const std::function<void()>& loaded = {});

}  // namespace sacfuse
