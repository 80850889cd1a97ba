#pragma once
// fusion.method as an enum, parsed once by the config (config/option_table.cc). The one name <-> enum table:
// the schema's choices, --print-defaults and `sacfuse bench --methods` all read FusionMethodNames().
#include <optional>
#include <string>
#include <vector>

namespace sacfuse {

enum class FusionMethodKind { kSac, kUnion, kConsistency, kDisparityNormal, kTsdf, kMultiray };

struct FusionMethodName {
  FusionMethodKind kind;
  const char* name;  // the YAML value of fusion.method
};

// Every method in the order of the docs and of `sacfuse bench`: sac, union, consistency, disparity_normal, tsdf,
// multiray.
const std::vector<FusionMethodName>& FusionMethodNames();
// The names alone, in that order.
std::vector<std::string> FusionMethodNameList();
std::string NameOf(FusionMethodKind kind);
// nullopt for a name that is no method.
std::optional<FusionMethodKind> FusionMethodFromName(const std::string& name);

}  // namespace sacfuse
