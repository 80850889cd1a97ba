#include "jobs/convert_input.h"

#include <functional>
#include <map>

#include "core/error.h"

namespace sacfuse {
namespace {

using Converter = std::function<InputOptions(const DepthBlock&, const std::string& out_dir)>;

// One entry per writable input format.
const std::map<std::string, Converter>& Converters() {
  static const std::map<std::string, Converter> converters = {
  };
  return converters;
}

}  // namespace

std::vector<std::string> ConversionTargets() {
  std::vector<std::string> names;
  for (const auto& [name, converter] : Converters()) names.push_back(name);
  return names;
}

InputOptions ConvertInput(const DepthBlock& input, const std::string& target, const std::string& out_dir) {
  const auto it = Converters().find(target);
  if (it == Converters().end()) {
    std::string known;
    for (const std::string& name : ConversionTargets()) known += (known.empty() ? "" : ", ") + name;
    throw ConfigError("--to " + target + ": unknown target format (known: " + known + ")");
  }
  return it->second(input, out_dir);
}

}  // namespace sacfuse
