#pragma once
// Repeated keys in a YAML mapping. yaml-cpp keeps every pair of a mapping with a repeated key, but a lookup by key
// sees only one of them, so a repeat silently wins or loses; every reader of user YAML (job configs, camera
// files) refuses repeats through this one check.
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace sacfuse {

struct YamlRepeatedKey {
  std::string key;     // the scalar text of the key
  size_t index = 0;    // position of the repeat among the mapping's pairs (0-based)
  int line = 0;        // 1-based line of the repeat
  int first_line = 0;  // 1-based line of its first occurrence
};

// The repeats among the keys of `map`, in file order (empty for a node that is not a mapping).
std::vector<YamlRepeatedKey> RepeatedYamlKeys(const YAML::Node& map);

// "duplicate key (first on line N); YAML keeps only one of them: remove or merge the other"
std::string RepeatedYamlKeyProblem(const YamlRepeatedKey& repeat);

}  // namespace sacfuse
