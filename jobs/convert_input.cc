#include "jobs/convert_input.h"

#include <functional>
#include <map>

#include "core/error.h"
#include "io/openmvs_block.h"
#include "jobs/convert_rasters.h"

namespace sacfuse {
namespace {

using Converter = std::function<InputOptions(const DepthBlock&, const std::string& out_dir)>;

// One entry per writable input format.
const std::map<std::string, Converter>& Converters() {
  static const std::map<std::string, Converter> converters = {
      {"openmvs",  // depth%04u.dmap + images/*.png (io/openmvs_block.h)
       [](const DepthBlock& input, const std::string& out_dir) {
         WriteOpenMvsBlock(input, out_dir);
         InputOptions options;
         options.format = "openmvs";
         options.path = out_dir;
         return options;
       }},
  };
  return converters;
}

// Targets that also need the job's context (jobs/convert_rasters.h: the rasters family).
using ContextConverter =
    std::function<InputOptions(const DepthBlock&, const std::string& out_dir, const ConvertContext&)>;
const std::map<std::string, ContextConverter>& ContextConverters() {
  static const std::map<std::string, ContextConverter> converters = [] {
    std::map<std::string, ContextConverter> m;
    for (const std::string& target : RasterTargets()) {
      m[target] = [target](const DepthBlock& input, const std::string& out_dir, const ConvertContext& context) {
        return ConvertToRasters(input, target, out_dir, context.crs);
      };
    }
    return m;
  }();
  return converters;
}

}  // namespace

std::vector<std::string> ConversionTargets() {
  std::vector<std::string> names;
  for (const auto& [name, converter] : Converters()) names.push_back(name);
  for (const auto& [name, converter] : ContextConverters()) names.push_back(name);
  return names;
}

InputOptions ConvertInput(const DepthBlock& input, const std::string& target, const std::string& out_dir,
                          const ConvertContext& context) {
  if (const auto c = ContextConverters().find(target); c != ContextConverters().end()) {
    return c->second(input, out_dir, context);
  }
  const auto it = Converters().find(target);
  if (it == Converters().end()) {
    std::string known;
    for (const std::string& name : ConversionTargets()) known += (known.empty() ? "" : ", ") + name;
    throw ConfigError("--to " + target + ": unknown target format (known: " + known + ")");
  }
  return it->second(input, out_dir);
}

}  // namespace sacfuse
