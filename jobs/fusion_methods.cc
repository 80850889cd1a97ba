#include "jobs/fusion_methods.h"

#include "core/error.h"
#include "core/fusion_methods.h"

namespace sacfuse {

std::unique_ptr<FusionMethod> MakeFusionMethod(const FusionOptions& fusion, const SacProgress& progress) {
  switch (fusion.method) {
    case FusionMethodKind::kSac: return MakeSacMethod(fusion.sac, progress);
    case FusionMethodKind::kUnion: return MakeUnionMethod();
    case FusionMethodKind::kConsistency: return MakeConsistencyMethod(fusion.consistency);
    case FusionMethodKind::kDisparityNormal: return MakeDisparityNormalMethod(fusion.disparity_normal);
    case FusionMethodKind::kMultiray: return MakeMultirayMethod(fusion.multiray);
    case FusionMethodKind::kTsdf: return MakeTsdfMethod(fusion.tsdf);
  }
  throw ConfigError("fusion.method = " + std::to_string(static_cast<int>(fusion.method)) + ": unknown method");
}

}  // namespace sacfuse
