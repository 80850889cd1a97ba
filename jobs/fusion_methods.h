#pragma once
// fusion.method -> the method (core/fusion_methods.h): sac | union | consistency | disparity_normal | tsdf |
// multiray, all run the same way on a whole block or a tile's windows (jobs/fuse_views.h).
#include <memory>

#include "config/job_config.h"
#include "core/fusion_method.h"
#include "core/sac_fusion.h"

namespace sacfuse {

// Throws ConfigError naming fusion.method for an unknown method. `progress` reaches SAC's collapse only.
std::unique_ptr<FusionMethod> MakeFusionMethod(const FusionOptions& fusion, const SacProgress& progress = {});

}  // namespace sacfuse
