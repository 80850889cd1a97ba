#include "config/config_override.h"

#include "core/error.h"

namespace sacfuse {

std::string ConfigOverride::Describe() const {
  if (option == "--set") return option + " " + key + "=" + value;
  return option + " " + value;
}

ConfigOverride ParseSetOption(const std::string& text) {
  const size_t equals = text.find('=');
  ConfigOverride o;
  if (equals != std::string::npos) {
    o.key = text.substr(0, equals);
    o.value = text.substr(equals + 1);
  }
  // Spaces around the key are the shell's doing (`--set "fusion.tau_m = 1"`); the value is YAML and keeps them.
  while (!o.key.empty() && o.key.back() == ' ') o.key.pop_back();
  while (!o.key.empty() && o.key.front() == ' ') o.key.erase(0, 1);
  if (equals == std::string::npos || o.key.empty()) {
    throw ConfigError("--set " + text + ": expected KEY=VALUE with a config key such as fusion.tau_m=1.0 (see "
                      "`sacfuse run --print-defaults`)");
  }
  return o;
}

}  // namespace sacfuse
