#include "jobs/fusion_methods.h"

#include "core/error.h"
#include "core/fusion_methods.h"

namespace sacfuse {

std::unique_ptr<FusionMethod> MakeFusionMethod(const FusionOptions& fusion, const SacProgress& progress) {
  const std::string& m = fusion.method;
  if (m == "sac") return MakeSacMethod(fusion.sac, progress);
  if (m == "union") return MakeUnionMethod();
  if (m == "consistency") return MakeConsistencyMethod(fusion.consistency);
  if (m == "disparity_normal") return MakeDisparityNormalMethod(fusion.disparity_normal);
  if (m == "multiray") return MakeMultirayMethod(fusion.multiray);
  if (m == "tsdf") return MakeTsdfMethod(fusion.tsdf);
  throw ConfigError("fusion.method = " + m + ": unknown method");
}

}  // namespace sacfuse
