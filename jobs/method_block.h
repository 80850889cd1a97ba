#pragma once
// A comparison method (fusion.method other than sac and union) over a whole block held in memory: every view's
// depth map and its colours resampled to the depth grid (the same colours a tile reads from the colour cache),
// no superpixels; then jobs/fusion_methods.h. The untiled path; tiles run the same through jobs/tiled_sac.h.
#include "config/job_config.h"
#include "core/method_stats.h"
#include "core/point.h"
#include "core/sac_fusion.h"
#include "io/depth_block.h"

namespace sacfuse {

struct MethodBlockResult {
  MethodStats stats;
  double load_seconds = 0.0;  // reading depth maps and images
};

MethodBlockResult FuseWorkspaceWithMethod(const DepthBlock& input, const JobConfig& config, PointSink& sink,
                                          const SacProgress& progress = {});

}  // namespace sacfuse
