#pragma once
// A table of YAML keys bound to struct fields: parse YAML into the fields with precise errors, dump the fields
// back as commented YAML. Generic (knows nothing of sacfuse's options; job_config.cc fills it).
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace YAML {
class Node;
}

namespace sacfuse {

// Every number of a config (AddDouble, AddFloat, AddInt, AddDoubleList) must be finite and at most this in
// magnitude; Parse reports "<key> = <value>: must be a finite number ..." for any other, whatever the key.
constexpr double kMaxConfigMagnitude = 1e9;

class ConfigSchema {
 public:
  // Each binder keeps a pointer to the field; the schema must not outlive the struct.
  void AddString(const std::string& key, std::string* field, const std::string& doc,
                 std::vector<std::string> allowed = {});
  void AddDouble(const std::string& key, double* field, const std::string& doc);
  void AddFloat(const std::string& key, float* field, const std::string& doc);
  void AddInt(const std::string& key, int* field, const std::string& doc);
  void AddBool(const std::string& key, bool* field, const std::string& doc);
  void AddDoubleList(const std::string& key, std::vector<double>* field, const std::string& doc);

  // Fills the bound fields from `root` (a YAML mapping). Collects every problem: unknown keys (with the keys
  // allowed there), repeated keys, wrong types, values not in `allowed`, numbers that are not finite or exceed
  // kMaxConfigMagnitude; each message is "<source>:<line>: <key>: <problem>" or, for a broken rule on a value,
  // "<source>:<line>: <key> = <value>: <rule>".
  // Throws ConfigError listing them all.
  // `key_lines`, when given, receives the 1-based line of every key present in the YAML.
  void Parse(const YAML::Node& root, const std::string& source,
             std::map<std::string, int>* key_lines = nullptr) const;
  // YAML text of the current field values, sections in registration order; comments carry the docs.
  std::string Dump(bool with_comments) const;
  // Every key with its current value as YAML scalar/flow text, in registration order.
  std::vector<std::pair<std::string, std::string>> Values() const;

 private:
  struct Entry {
    std::string key;  // dotted path
    std::string doc;
    std::vector<std::string> allowed;
    std::function<std::string(const YAML::Node&)> set;  // returns "" or a problem
    std::function<std::string()> get;                    // YAML scalar/flow text
  };
  const Entry* Find(const std::string& key) const;
  void ParseMap(const YAML::Node& node, const std::string& prefix, const std::string& source,
                std::vector<std::string>* errors, std::map<std::string, int>* key_lines) const;
  std::vector<Entry> entries_;
};

}  // namespace sacfuse
