#pragma once
// The fusion methods a job can run besides SAC (fusion.method: union | consistency | disparity_normal | tsdf |
// multiray), dispatched on views held in memory: a whole block (jobs/method_block.h) or a tile's windows
// (jobs/tiled_sac.h). Same inputs, tiles and LAS outputs as SAC, so differences in the results are the methods'.
#include <string>
#include <vector>

#include "config/job_config.h"
#include "core/method_stats.h"
#include "core/method_views.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

// Whether a method reads superpixels (only sac); the others need only depth and colour.
bool MethodUsesSuperpixels(const std::string& method);

// Runs fusion.method (not sac) on `views`, whose neighbours and order are `plan` (positions in `views`), with the
// block GSD `gsd_m` (tsdf voxel size). `region_xy` (a tile's halo box) bounds tsdf's voxel grid. Throws
// ConfigError for an unknown method.
MethodStats RunFusionMethod(const FusionOptions& fusion, const std::vector<SacView>& views, const ViewPlan& plan,
                            double gsd_m, PointSink& sink, const FootprintBox* region_xy = nullptr);

}  // namespace sacfuse
