#include "core/option_check.h"

#include "core/error.h"

namespace sacfuse {

void OptionChecker::OneOf(const std::string& key, const std::string& value, const std::vector<std::string>& allowed) {
  for (const auto& a : allowed) {
    if (a == value) return;
  }
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  errors_.push_back(key + " = \"" + value + "\": must be one of {" + list + "}");
}

void OptionChecker::NotEmpty(const std::string& key, const std::string& value) {
  if (value.empty()) errors_.push_back(key + " is empty: a value is required");
}

void OptionChecker::Require(bool ok, const std::string& key, const std::string& value, const std::string& rule) {
  if (!ok) errors_.push_back(key + " = " + value + ": " + rule);
}

void OptionChecker::ThrowIfFailed(const std::string& where) const {
  if (errors_.empty()) return;
  std::string msg = where + ": invalid configuration";
  for (const auto& e : errors_) msg += "\n  " + e;
  throw ConfigError(msg);
}

}  // namespace sacfuse
