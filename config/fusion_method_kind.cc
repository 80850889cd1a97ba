#include "config/fusion_method_kind.h"

namespace sacfuse {

const std::vector<FusionMethodName>& FusionMethodNames() {
  static const std::vector<FusionMethodName> names = {
      {FusionMethodKind::kSac, "sac"},   {FusionMethodKind::kUnion, "union"},
      {FusionMethodKind::kConsistency, "consistency"}, {FusionMethodKind::kDisparityNormal, "disparity_normal"},
      {FusionMethodKind::kTsdf, "tsdf"}, {FusionMethodKind::kMultiray, "multiray"}};
  return names;
}

std::vector<std::string> FusionMethodNameList() {
  std::vector<std::string> list;
  for (const FusionMethodName& m : FusionMethodNames()) list.emplace_back(m.name);
  return list;
}

std::string NameOf(FusionMethodKind kind) {
  for (const FusionMethodName& m : FusionMethodNames()) {
    if (m.kind == kind) return m.name;
  }
  return "";
}

std::optional<FusionMethodKind> FusionMethodFromName(const std::string& name) {
  for (const FusionMethodName& m : FusionMethodNames()) {
    if (name == m.name) return m.kind;
  }
  return std::nullopt;
}

}  // namespace sacfuse
