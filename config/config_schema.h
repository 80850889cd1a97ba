#pragma once
// A table of YAML keys bound to struct fields, each with its unit, range (or choices), doc, whether it affects
// results, and the scopes that read it: parse YAML into the fields with precise errors, check every range after
// parsing (structured errors), dump the fields back as commented YAML. Generic (knows nothing of sacfuse's
// options; config/option_table.cc fills it).
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "config/config_override.h"

namespace YAML {
class Node;
}

namespace sacfuse {

// Every number of a config (AddDouble, AddFloat, AddInt, AddDoubleList) must be finite and at most this in
// magnitude; Parse reports "<key> = <value>: must be a finite number ..." for any other, whatever the key.
constexpr double kMaxConfigMagnitude = 1e9;

// One broken rule: formatted once by FormatOptionError as "<key> = <value>: <rule>" ("<key> is empty: <rule>"
// when `value` is empty), and by OptionErrorsMessage with the file and line of the key.
struct OptionError {
  std::string key;    // dotted YAML key
  std::string value;  // as the message shows it (numbers as C++ streams print them; choices quoted)
  std::string rule;   // e.g. "must be > 0"
};
std::string FormatOptionError(const OptionError& error);
// Where each key given by the user was given, as the prefix of its messages: "<source>:<line>: " for a key of the
// YAML file, "--set " for one set on the command line (ConfigOverride::option).
using KeyPlaces = std::map<std::string, std::string>;
// "<source>: invalid configuration" and one indented line per error, each key's place before the errors of keys
// present in `key_places` (so range errors point at the line or option like type errors do).
std::string OptionErrorsMessage(const std::vector<OptionError>& errors, const std::string& source,
                                const KeyPlaces& key_places = {});
// Numbers in messages, as the rules print their bounds ("0.5", "1e-06").
std::string OptionValueText(double value);

// The values a key allows. Numbers: [min, max] with open or closed ends (every number is also within
// +-kMaxConfigMagnitude). Strings: one of `choices`, or any text (`choices` empty; `required`: not empty).
struct OptionRange {
  double min = -kMaxConfigMagnitude;
  double max = kMaxConfigMagnitude;
  bool min_open = false;
  bool max_open = false;
  std::vector<std::string> choices;
  bool required = false;
  bool is_text = false;  // a string key: choices or free text; else a number (or a list of numbers)

  bool Contains(double value) const;
  // "must be > 0", "must be in (0, 0.5]", "must be one of {a, b}", "any text", ...
  std::string Rule() const;
};
OptionRange AnyNumber();                        // [-1e9, 1e9]
OptionRange Above(double min);                  // (min, 1e9]
OptionRange AtLeast(double min);                // [min, 1e9]
OptionRange Closed(double min, double max);     // [min, max]
OptionRange OpenClosed(double min, double max);  // (min, max]
OptionRange Choices(std::vector<std::string> choices);
OptionRange AnyText();
OptionRange RequiredText();                     // any text but ""

// Bit masks of the scopes a key is read in (sacfuse: fusion methods); Check validates only the keys of the scopes
// in use.
constexpr uint32_t kEveryScope = ~0u;

struct OptionSpec {
  std::string unit;  // "m", "deg", "px", "GiB", ...; "-" for none
  OptionRange range;
  bool affects_results = true;  // part of the result-affecting settings (resume hash)
  uint32_t scopes = kEveryScope;
};

// One row of the table as data (tests, docs): the key, its type, current value as YAML, doc and spec.
struct OptionRow {
  std::string key;
  std::string type;   // "text", "number", "whole number", "true or false", "list of numbers", "choice"
  std::string value;  // YAML scalar/flow text
  std::string doc;
  OptionSpec spec;
};

class ConfigSchema {
 public:
  // Each binder keeps a pointer to the field; the schema must not outlive the struct.
  void AddString(const std::string& key, std::string* field, OptionSpec spec, const std::string& doc);
  void AddDouble(const std::string& key, double* field, OptionSpec spec, const std::string& doc);
  void AddFloat(const std::string& key, float* field, OptionSpec spec, const std::string& doc);
  void AddInt(const std::string& key, int* field, OptionSpec spec, const std::string& doc);
  void AddBool(const std::string& key, bool* field, OptionSpec spec, const std::string& doc);
  void AddDoubleList(const std::string& key, std::vector<double>* field, OptionSpec spec, const std::string& doc);
  // An enum field parsed from its name: `names` pairs each enumerator with its YAML value (the choices).
  template <typename E>
  void AddEnum(const std::string& key, E* field, const std::vector<std::pair<E, std::string>>& names,
               OptionSpec spec, const std::string& doc) {
    std::vector<std::string> choices;
    for (const auto& n : names) choices.push_back(n.second);
    AddChoice(
        key, [field, names] { return IndexOf(names, *field); },
        [field, names](size_t i) { *field = names[i].first; }, choices, std::move(spec), doc);
  }

  // Fills the bound fields from `root` (a YAML mapping), then from `overrides` in order (each as if its key were
  // in the file, later ones winning). Collects every problem: unknown keys (with the keys allowed there), repeated
  // keys, wrong types, values not in the choices, numbers that are not finite or exceed kMaxConfigMagnitude; each
  // message is "<place><key>: <problem>" or, for a broken rule on a value, "<place><key> = <value>: <rule>", the
  // place being "<source>:<line>: " or the override's option ("--set ").
  // Throws ConfigError listing them all.
  // `key_places`, when given, receives the place of every key present in the YAML or overridden.
  void Parse(const YAML::Node& root, const std::string& source, const std::vector<ConfigOverride>& overrides = {},
             KeyPlaces* key_places = nullptr) const;
  // The range (or choices) of every key read by one of `scopes`, on the current field values.
  std::vector<OptionError> Check(uint32_t scopes) const;
  // YAML text of the current field values, sections in registration order; comments carry the docs.
  std::string Dump(bool with_comments) const;
  // Every key with its current value as YAML scalar/flow text, in registration order.
  std::vector<std::pair<std::string, std::string>> Values() const;
  std::vector<OptionRow> Rows() const;

 private:
  struct Entry {
    std::string key;  // dotted path
    std::string type;
    std::string doc;
    OptionSpec spec;
    std::function<std::string(const YAML::Node&)> set;  // returns "" or a problem
    std::function<std::string()> get;                    // YAML scalar/flow text
    std::function<std::vector<OptionError>()> check;     // the range on the current value
  };
  template <typename E>
  static size_t IndexOf(const std::vector<std::pair<E, std::string>>& names, E value) {
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i].first == value) return i;
    }
    return names.size();
  }
  void AddChoice(const std::string& key, std::function<size_t()> get_index, std::function<void(size_t)> set_index,
                 const std::vector<std::string>& choices, OptionSpec spec, const std::string& doc);
  template <typename T>
  void AddNumber(const std::string& key, T* field, const char* type, int digits, OptionSpec spec,
                 const std::string& doc);
  const Entry* Find(const std::string& key) const;
  bool IsSection(const std::string& key) const;
  // "allowed in <prefix>: a, b" (or "allowed at the top level: ..."): the keys and sections directly under `prefix`.
  std::string AllowedKeys(const std::string& prefix) const;
  void ParseMap(const YAML::Node& node, const std::string& prefix, const std::string& source,
                std::vector<std::string>* errors, KeyPlaces* key_places) const;
  void ParseOverride(const ConfigOverride& o, std::vector<std::string>* errors, KeyPlaces* key_places) const;
  std::vector<Entry> entries_;
};

}  // namespace sacfuse
