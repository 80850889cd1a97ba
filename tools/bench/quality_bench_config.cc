#include "tools/bench/quality_bench_config.h"

#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "core/error.h"

namespace sacfuse::bench {
namespace {

namespace fs = std::filesystem;

YAML::Node LoadBlockConfig(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw InputError(path, std::string("cannot read the block config: ") + e.what());
  }
  if (!root.IsMap()) throw InputError(path, "the block config is not a YAML mapping");
  return root;
}

// Relative paths in a block config are relative to its folder.
std::string Absolute(const std::string& value, const fs::path& base) {
  if (value.empty()) return value;
  const fs::path p(value);
  std::string out = (p.is_absolute() ? p : (base / p)).lexically_normal().string();
  while (out.size() > 1 && out.back() == '/') out.pop_back();  // "." -> the folder itself
  return out;
}

void MakeAbsolute(YAML::Node root, const char* section, const char* key, const fs::path& base) {
  if (!root[section] || !root[section].IsMap()) return;
  YAML::Node node = root[section][key];
  if (!node || !node.IsScalar()) return;
  root[section][key] = Absolute(node.as<std::string>(), base);
}

// Sets node[a][b]... for key "a.b..."; `full_key` is the whole key, for messages.
void SetDotted(YAML::Node node, const std::string& key, const std::string& value, const std::string& full_key) {
  const size_t dot = key.find('.');
  if (dot == std::string::npos) {
    node[key] = YAML::Load(value);
    return;
  }
  const std::string head = key.substr(0, dot);
  if (node[head] && !node[head].IsMap()) {
    throw ConfigError("bench row key '" + full_key + "': '" + head + "' is not a mapping in the block config");
  }
  if (!node[head]) node[head] = YAML::Node(YAML::NodeType::Map);
  SetDotted(node[head], key.substr(dot + 1), value, full_key);
}

}  // namespace

std::string MakeRowConfig(const RowConfigRequest& request) {
  YAML::Node root = LoadBlockConfig(request.block_config);
  const fs::path base = fs::absolute(request.block_config).parent_path();
  MakeAbsolute(root, "input", "path", base);
  MakeAbsolute(root, "input", "cameras", base);
  MakeAbsolute(root, "evaluation", "reference", base);
  MakeAbsolute(root, "evaluation", "mask", base);
  MakeAbsolute(root, "fusion", "superpixel_cache_dir", base);
  if (root["output"] && !root["output"].IsMap()) throw InputError(request.block_config, "output is not a mapping");
  root["output"]["dir"] = fs::absolute(request.output_dir).lexically_normal().string();  // a string, never parsed
  root["output"]["format"] = "las";  // uncompressed: what the bench's scorers (ours and aerial-bench's) read fastest
  if (!request.keep_evaluation) root.remove("evaluation");
  for (const auto& [key, value] : request.overrides) SetDotted(root, key, value, key);
  YAML::Emitter out;
  out << root;
  return std::string("# Written by `sacfuse bench` from ") + request.block_config + "\n" + out.c_str() + "\n";
}

BlockEvaluation ReadBlockEvaluation(const std::string& block_config) {
  const YAML::Node root = LoadBlockConfig(block_config);
  const fs::path base = fs::absolute(block_config).parent_path();
  BlockEvaluation e;
  const YAML::Node ev = root["evaluation"];
  if (!ev || !ev.IsMap()) return e;
  try {
    if (ev["reference"]) e.reference = Absolute(ev["reference"].as<std::string>(), base);
    if (ev["mask"]) e.mask = Absolute(ev["mask"].as<std::string>(), base);
    if (ev["gsd_m"]) e.gsd_m = ev["gsd_m"].as<double>();
    if (ev["tau_gsd"]) e.tau_gsd = ev["tau_gsd"].as<std::vector<double>>();
    if (ev["align"]) e.align = ev["align"].as<bool>();
  } catch (const YAML::Exception& ex) {
    throw InputError(block_config, std::string("evaluation section: ") + ex.what());
  }
  return e;
}

}  // namespace sacfuse::bench
