#pragma once
// A config key set on the command line (`--set fusion.tau_m=1.0`, `--output-dir DIR`, `run --threads N`): applied
// after the YAML file and before validation, so it is checked, recorded in sacfuse.effective.yaml and taken into
// the resume hash exactly like the same key in the file; messages name the option instead of file:line.
#include <string>
#include <vector>

namespace sacfuse {

struct ConfigOverride {
  std::string key;        // dotted YAML key, e.g. "fusion.tau_m"
  std::string value;      // the value as YAML text ("1.0", "[2, 5]", "\"EPSG:25832\""; "" = the empty string)
  bool literal = false;   // the value is a plain string, not read as YAML (paths of --output-dir)
  std::string option = "--set";  // the command-line option that gave it, for messages

  // "--set fusion.tau_m=1.0", "--output-dir /data/out": the override as the user typed it.
  std::string Describe() const;
};

// `--set KEY=VALUE` (split at the first '='); throws ConfigError when there is no '=' or no key.
ConfigOverride ParseSetOption(const std::string& text);

}  // namespace sacfuse
