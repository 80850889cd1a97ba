#pragma once
// Validation helpers for option structs: each failed rule becomes one message naming the option, the value and
// the rule, e.g. "SacOptions.tau_m = -1: must be > 0". All messages are collected and thrown together. Used for
// core's own invariants and the options of tools' commands; the YAML keys of `sacfuse run` are checked from the
// table in config/option_table.cc.
#include <sstream>
#include <string>
#include <vector>

namespace sacfuse {

class OptionChecker {
 public:
  template <typename T>
  void Greater(const std::string& key, const T& value, const T& bound) {
    if (!(value > bound)) Fail(key, value, "must be > " + ToString(bound));
  }
  template <typename T>
  void AtLeast(const std::string& key, const T& value, const T& bound) {
    if (!(value >= bound)) Fail(key, value, "must be >= " + ToString(bound));
  }
  template <typename T>
  void AtMost(const std::string& key, const T& value, const T& bound) {
    if (!(value <= bound)) Fail(key, value, "must be <= " + ToString(bound));
  }
  template <typename T>
  void InRange(const std::string& key, const T& value, const T& lo, const T& hi) {
    if (!(value >= lo && value <= hi)) Fail(key, value, "must be in [" + ToString(lo) + ", " + ToString(hi) + "]");
  }
  void OneOf(const std::string& key, const std::string& value, const std::vector<std::string>& allowed);
  void NotEmpty(const std::string& key, const std::string& value);
  void Require(bool ok, const std::string& key, const std::string& value, const std::string& rule);

  bool ok() const { return errors_.empty(); }
  const std::vector<std::string>& errors() const { return errors_; }
  // Throws ConfigError listing every failed rule (prefixed with `where`, e.g. the config file) when any failed.
  void ThrowIfFailed(const std::string& where) const;

  template <typename T>
  static std::string ToString(const T& v) {
    std::ostringstream os;
    os << v;
    return os.str();
  }

 private:
  template <typename T>
  void Fail(const std::string& key, const T& value, const std::string& rule) {
    errors_.push_back(key + " = " + ToString(value) + ": " + rule);
  }
  std::vector<std::string> errors_;
};

}  // namespace sacfuse
