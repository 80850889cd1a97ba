#pragma once
// Test helper for the config tests: the ConfigError message a YAML text produces.
#include <string>

#include "config/job_config.h"
#include "core/error.h"

namespace sacfuse {

// Parses `yaml` as job.yaml with relative paths against /base; returns the ConfigError's message, or "" when the
// text is a valid config.
inline std::string ConfigErrorOf(const std::string& yaml) {
  try {
    ParseJobConfig(yaml, "job.yaml", "/base");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace sacfuse
