#pragma once
// `sacfuse bench`, part 2: the config of one row. The block's sacfuse.yaml (written by `sacfuse simulate`) is
// loaded as a YAML tree, its paths made absolute (they are relative to the block folder), output.dir set to the
// row's folder and the row's keys set (e.g. fusion.method: tsdf, fusion.unary: paper); every other key keeps the
// block's value or the default, so a row shows what users get. The config goes next to the row's output.
#include <string>
#include <utility>
#include <vector>

namespace sacfuse::bench {

struct RowConfigRequest {
  std::string block_config;   // the block's sacfuse.yaml
  std::string output_dir;     // -> output.dir (absolute)
  std::vector<std::pair<std::string, std::string>> overrides;  // dotted key -> value (parsed as a YAML scalar)
  bool keep_evaluation = true;  // false: drop the evaluation section (the bench scores in a separate step)
};

// The row's config as YAML text. Throws InputError (naming the file) when the block config cannot be read or is
// not a mapping, ConfigError when an override's key runs into a non-mapping value.
std::string MakeRowConfig(const RowConfigRequest& request);

// The evaluation settings of a block config (paths absolute), as `sacfuse eval` takes them.
struct BlockEvaluation {
  std::string reference;      // "" = the block has no reference
  std::string mask;
  double gsd_m = 0.10;
  std::vector<double> tau_gsd = {2.0, 5.0};
  bool align = false;
};
BlockEvaluation ReadBlockEvaluation(const std::string& block_config);

}  // namespace sacfuse::bench
