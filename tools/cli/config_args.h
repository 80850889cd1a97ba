#pragma once
// The options of every command that reads a job's YAML config: CONFIG, `--set KEY=VALUE` (repeatable) and
// `--output-dir DIR`. They become ConfigOverride's (config/config_override.h) applied on top of the file before
// validation, so `sacfuse run job.yaml --set fusion.tau_m=1` runs, records and hashes exactly what a job.yaml
// with `fusion: {tau_m: 1}` would; `status`, `tile` and `merge` need the same --set as the run they follow.
#include <string>
#include <vector>

#include "config/job_config.h"

namespace CLI {
class App;
}

namespace sacfuse::cli {

struct ConfigArgs {
  std::string path;
  std::vector<std::string> set;  // KEY=VALUE, in order (a later one wins)
  std::string output_dir;        // "" = output.dir of the config
  std::vector<ConfigOverride> more;  // a command's own options that set a key (run --threads), applied last

  // The config with its overrides: --set in order, then --output-dir, then `more`.
  JobConfig Load() const;
  // "job.yaml --set 'fusion.tau_m=1' --output-dir out": the words to repeat in a hint such as "rerun them with
  // sacfuse run <words> --tiles ...", shell-quoted where needed.
  std::string Words() const;
};

// Adds CONFIG (a positional; required unless `required` is false), --set and, with `output_dir`, --output-dir.
void AddConfigOptions(CLI::App* cmd, ConfigArgs* args, const std::string& config_help, bool required = true,
                      bool output_dir = true);

}  // namespace sacfuse::cli
