#include "io/yaml_keys.h"

#include <map>

#include <yaml-cpp/yaml.h>

namespace sacfuse {

std::vector<YamlRepeatedKey> RepeatedYamlKeys(const YAML::Node& map) {
  std::vector<YamlRepeatedKey> repeats;
  if (!map.IsMap()) return repeats;
  std::map<std::string, int> first_lines;
  size_t index = 0;
  for (const auto& kv : map) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : YAML::Dump(kv.first);
    const int line = kv.first.Mark().line + 1;
    const auto [it, fresh] = first_lines.emplace(key, line);
    if (!fresh) repeats.push_back({key, index, line, it->second});
    ++index;
  }
  return repeats;
}

std::string RepeatedYamlKeyProblem(const YamlRepeatedKey& repeat) {
  return "duplicate key (first on line " + std::to_string(repeat.first_line) +
         "); YAML keeps only one of them: remove or merge the other";
}

}  // namespace sacfuse
