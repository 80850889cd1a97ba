#include "config/config_schema.h"

#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>
#include <type_traits>

#include <yaml-cpp/yaml.h>

#include "core/error.h"
#include "io/yaml_keys.h"

namespace sacfuse {
namespace {

std::string NodeKind(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Null: return "nothing (null)";
    default: return "\"" + n.Scalar() + "\"";
  }
}

std::string FormatDouble(double v, int digits = 15) {
  std::ostringstream os;
  os << std::setprecision(digits) << v;
  std::string s = os.str();
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string Quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// A broken rule on a value, as ParseMap prints it after the key: "<key> = <value as written>: <rule>".
std::string RuleBroken(const YAML::Node& n, const std::string& rule) { return "= " + n.Scalar() + ": " + rule; }

template <typename T>
std::string ScalarAs(const YAML::Node& n, T* out, const char* type_name) {
  if (!n.IsScalar()) return std::string("expected ") + type_name + ", got " + NodeKind(n);
  T value{};
  try {
    value = n.as<T>();
  } catch (const YAML::Exception&) {
    return std::string("expected ") + type_name + ", got " + NodeKind(n);
  }
  // The one rule every number of every config obeys, whatever its key: finite (no .inf, -.inf, .nan) and of a
  // magnitude no sacfuse setting needs to exceed (coordinates, sizes, budgets; each key's own range is checked
  // by its validator on top).
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    const double v = static_cast<double>(value);
    if (!std::isfinite(v)) return RuleBroken(n, "must be a finite number");
    if (std::abs(v) > kMaxConfigMagnitude) {
      return RuleBroken(n, "must be a finite number in [-1e9, 1e9]");
    }
  }
  *out = value;
  return "";
}

std::string ChoiceList(const std::vector<std::string>& choices) {
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  return list;
}

// "" when `v` is one of `choices`, else the problem as ParseMap prints it after the key.
std::string NotAChoice(const std::string& v, const std::vector<std::string>& choices) {
  for (const auto& c : choices) {
    if (c == v) return "";
  }
  return "\"" + v + "\" is not one of {" + ChoiceList(choices) + "}";
}

// A problem of Entry::set after "<place><key>": a broken rule reads "<key> = <value>: <rule>" like the validators'
// messages, a type error "<key>: ...".
std::string KeyProblem(const std::string& place, const std::string& key, const std::string& problem) {
  return problem.rfind("= ", 0) == 0 ? place + key + " " + problem : place + key + ": " + problem;
}

// The range rule on one number of `key`, or nothing.
void CheckNumber(const std::string& key, double v, const OptionRange& range, const std::string& rule_prefix,
                 std::vector<OptionError>* errors) {
  if (range.Contains(v)) return;
  const bool finite = std::isfinite(v) && std::abs(v) <= kMaxConfigMagnitude;
  errors->push_back({key, OptionValueText(v), rule_prefix + (finite ? range.Rule() : AnyNumber().Rule())});
}

}  // namespace

std::string FormatOptionError(const OptionError& e) {
  return e.value.empty() ? e.key + " is empty: " + e.rule : e.key + " = " + e.value + ": " + e.rule;
}

std::string OptionErrorsMessage(const std::vector<OptionError>& errors, const std::string& source,
                                const KeyPlaces& key_places) {
  std::string msg = source + ": invalid configuration";
  for (const OptionError& e : errors) {
    const auto place = key_places.find(e.key);
    msg += "\n  " + (place == key_places.end() ? "" : place->second) + FormatOptionError(e);
  }
  return msg;
}

std::string OptionValueText(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

bool OptionRange::Contains(double v) const {
  if (!std::isfinite(v) || std::abs(v) > kMaxConfigMagnitude) return false;
  return (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max);
}

std::string OptionRange::Rule() const {
  if (is_text) {
    if (!choices.empty()) return "must be one of {" + ChoiceList(choices) + "}";
    return required ? "a value is required" : "any text";
  }
  const bool no_min = min <= -kMaxConfigMagnitude && !min_open;
  const bool no_max = max >= kMaxConfigMagnitude && !max_open;
  if (no_min && no_max) return "must be a finite number in [-1e9, 1e9]";
  if (no_max) return (min_open ? "must be > " : "must be >= ") + OptionValueText(min);
  if (no_min) return (max_open ? "must be < " : "must be <= ") + OptionValueText(max);
  return std::string("must be in ") + (min_open ? "(" : "[") + OptionValueText(min) + ", " + OptionValueText(max) +
         (max_open ? ")" : "]");
}

OptionRange AnyNumber() { return OptionRange{}; }

OptionRange Above(double min) {
  OptionRange r;
  r.min = min;
  r.min_open = true;
  return r;
}

OptionRange AtLeast(double min) {
  OptionRange r;
  r.min = min;
  return r;
}

OptionRange Closed(double min, double max) {
  OptionRange r;
  r.min = min;
  r.max = max;
  return r;
}

OptionRange OpenClosed(double min, double max) {
  OptionRange r = Closed(min, max);
  r.min_open = true;
  return r;
}

OptionRange Choices(std::vector<std::string> choices) {
  OptionRange r = AnyText();
  r.choices = std::move(choices);
  return r;
}

OptionRange AnyText() {
  OptionRange r;
  r.is_text = true;
  return r;
}

OptionRange RequiredText() {
  OptionRange r = AnyText();
  r.required = true;
  return r;
}

void ConfigSchema::AddString(const std::string& key, std::string* field, OptionSpec spec, const std::string& doc) {
  const std::vector<std::string> choices = spec.range.choices;
  Entry e{key, choices.empty() ? "text" : "choice", doc, spec, nullptr, nullptr, nullptr};
  e.set = [field, choices](const YAML::Node& n) -> std::string {
    std::string v;
    if (auto err = ScalarAs(n, &v, "a string"); !err.empty()) return err;
    if (!choices.empty()) {
      if (auto err = NotAChoice(v, choices); !err.empty()) return err;
    }
    *field = v;
    return "";
  };
  e.get = [field] { return Quote(*field); };
  e.check = [key, field, range = spec.range]() -> std::vector<OptionError> {
    if (!range.choices.empty() && !NotAChoice(*field, range.choices).empty()) {
      return {{key, Quote(*field), range.Rule()}};
    }
    if (range.required && field->empty()) return {{key, "", range.Rule()}};
    return {};
  };
  entries_.push_back(std::move(e));
}

void ConfigSchema::AddChoice(const std::string& key, std::function<size_t()> get_index,
                             std::function<void(size_t)> set_index, const std::vector<std::string>& choices,
                             OptionSpec spec, const std::string& doc) {
  spec.range = Choices(choices);
  Entry e{key, "choice", doc, spec, nullptr, nullptr, nullptr};
  e.set = [set_index, choices](const YAML::Node& n) -> std::string {
    std::string v;
    if (auto err = ScalarAs(n, &v, "a string"); !err.empty()) return err;
    if (auto err = NotAChoice(v, choices); !err.empty()) return err;
    for (size_t i = 0; i < choices.size(); ++i) {
      if (choices[i] == v) set_index(i);
    }
    return "";
  };
  e.get = [get_index, choices] {
    const size_t i = get_index();
    return Quote(i < choices.size() ? choices[i] : "?");
  };
  e.check = [key, get_index, choices, rule = spec.range.Rule()]() -> std::vector<OptionError> {
    if (get_index() < choices.size()) return {};
    return {{key, "?", rule}};
  };
  entries_.push_back(std::move(e));
}

template <typename T>
void ConfigSchema::AddNumber(const std::string& key, T* field, const char* type, int digits, OptionSpec spec,
                             const std::string& doc) {
  const bool whole = std::is_integral_v<T>;
  Entry e{key, whole ? "whole number" : "number", doc, spec, nullptr, nullptr, nullptr};
  e.set = [field, type](const YAML::Node& n) { return ScalarAs(n, field, type); };
  e.get = [field, digits] {
    if constexpr (std::is_integral_v<T>) {
      return std::to_string(*field);
    } else {
      return FormatDouble(*field, digits);
    }
  };
  e.check = [key, field, range = spec.range] {
    std::vector<OptionError> errors;
    CheckNumber(key, static_cast<double>(*field), range, "", &errors);
    return errors;
  };
  entries_.push_back(std::move(e));
}

void ConfigSchema::AddDouble(const std::string& key, double* field, OptionSpec spec, const std::string& doc) {
  AddNumber(key, field, "a number", 15, std::move(spec), doc);
}

void ConfigSchema::AddFloat(const std::string& key, float* field, OptionSpec spec, const std::string& doc) {
  AddNumber(key, field, "a number", 7, std::move(spec), doc);
}

void ConfigSchema::AddInt(const std::string& key, int* field, OptionSpec spec, const std::string& doc) {
  AddNumber(key, field, "a whole number", 0, std::move(spec), doc);
}

void ConfigSchema::AddBool(const std::string& key, bool* field, OptionSpec spec, const std::string& doc) {
  spec.range = Choices({"true", "false"});
  Entry e{key, "true or false", doc, spec, nullptr, nullptr, nullptr};
  e.set = [field](const YAML::Node& n) { return ScalarAs(n, field, "true or false"); };
  e.get = [field] { return std::string(*field ? "true" : "false"); };
  e.check = [] { return std::vector<OptionError>{}; };
  entries_.push_back(std::move(e));
}

void ConfigSchema::AddDoubleList(const std::string& key, std::vector<double>* field, OptionSpec spec,
                                 const std::string& doc) {
  Entry e{key, "list of numbers", doc, spec, nullptr, nullptr, nullptr};
  e.set = [field](const YAML::Node& n) -> std::string {
    if (!n.IsSequence()) return "expected a list of numbers like [2, 5], got " + NodeKind(n);
    std::vector<double> values;
    for (const auto& item : n) {
      double v = 0;
      if (auto err = ScalarAs(item, &v, "a number in the list"); !err.empty()) return err;
      values.push_back(v);
    }
    *field = values;
    return "";
  };
  e.get = [field] {
    std::string s = "[";
    for (size_t i = 0; i < field->size(); ++i) s += (i ? ", " : "") + FormatDouble((*field)[i]);
    return s + "]";
  };
  e.check = [key, field, range = spec.range] {
    std::vector<OptionError> errors;
    if (range.required && field->empty()) errors.push_back({key, "[]", "must list at least one value"});
    for (const double v : *field) CheckNumber(key, v, range, "each item ", &errors);
    return errors;
  };
  entries_.push_back(std::move(e));
}

const ConfigSchema::Entry* ConfigSchema::Find(const std::string& key) const {
  for (const auto& e : entries_) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

bool ConfigSchema::IsSection(const std::string& key) const {
  for (const auto& e : entries_) {
    if (e.key.rfind(key + ".", 0) == 0) return true;
  }
  return false;
}

std::string ConfigSchema::AllowedKeys(const std::string& prefix) const {
  std::set<std::string> known;
  for (const auto& e : entries_) {
    if (prefix.empty() || e.key.rfind(prefix + ".", 0) == 0) {
      const std::string rest = prefix.empty() ? e.key : e.key.substr(prefix.size() + 1);
      known.insert(rest.substr(0, rest.find('.')));
    }
  }
  std::string list;
  for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
  return "allowed " + (prefix.empty() ? "at the top level" : "in " + prefix) + ": " + list;
}

void ConfigSchema::ParseMap(const YAML::Node& node, const std::string& prefix, const std::string& source,
                            std::vector<std::string>* errors, KeyPlaces* key_places) const {
  std::set<size_t> repeats;
  for (const YamlRepeatedKey& r : RepeatedYamlKeys(node)) {
    const std::string key = prefix.empty() ? r.key : prefix + "." + r.key;
    errors->push_back(source + ":" + std::to_string(r.line) + ": " + key + ": " + RepeatedYamlKeyProblem(r));
    repeats.insert(r.index);
  }
  size_t index = 0;
  for (const auto& kv : node) {
    const int line = kv.first.Mark().line + 1;
    if (repeats.count(index++) != 0) continue;  // reported above; the first occurrence is parsed
    const std::string name = kv.first.Scalar();
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    const std::string place = source + ":" + std::to_string(line) + ": ";
    if (key_places != nullptr) (*key_places)[key] = place;
    if (const Entry* e = Find(key)) {
      if (auto err = e->set(kv.second); !err.empty()) errors->push_back(KeyProblem(place, key, err));
      continue;
    }
    if (IsSection(key)) {
      if (!kv.second.IsMap()) {
        errors->push_back(place + key + ": expected a mapping (a section), got " + NodeKind(kv.second));
      } else {
        ParseMap(kv.second, key, source, errors, key_places);
      }
      continue;
    }
    errors->push_back(place + key + ": unknown key; " + AllowedKeys(prefix));
  }
}

void ConfigSchema::ParseOverride(const ConfigOverride& o, std::vector<std::string>* errors,
                                 KeyPlaces* key_places) const {
  const std::string place = o.option + " ";
  YAML::Node value;
  if (o.literal || o.value.empty()) {
    value = YAML::Node(o.value);  // `--set evaluation.mask=` is the empty string, as `mask: ""` in a file
  } else {
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::ParserException& e) {
      errors->push_back(place + o.key + ": " + Quote(o.value) + " is not valid YAML: " + e.msg);
      return;
    }
  }
  if (const Entry* e = Find(o.key)) {
    if (key_places != nullptr) (*key_places)[o.key] = place;
    if (auto err = e->set(value); !err.empty()) errors->push_back(KeyProblem(place, o.key, err));
    return;
  }
  if (IsSection(o.key)) {
    errors->push_back(place + o.key + ": a section, not a key: set its keys one by one (" + o.key + ".KEY=VALUE); " +
                      AllowedKeys(o.key));
    return;
  }
  // The deepest section the key starts with names the keys allowed there.
  std::string prefix = o.key;
  while (!prefix.empty() && !IsSection(prefix)) {
    const size_t dot = prefix.rfind('.');
    prefix = dot == std::string::npos ? "" : prefix.substr(0, dot);
  }
  errors->push_back(place + o.key + ": unknown key; " + AllowedKeys(prefix));
}

void ConfigSchema::Parse(const YAML::Node& root, const std::string& source,
                         const std::vector<ConfigOverride>& overrides, KeyPlaces* key_places) const {
  std::vector<std::string> errors;
  // An empty file means all defaults.
  if (!root.IsNull() && !root.IsMap()) {
    throw ConfigError(source + ":" + std::to_string(root.Mark().line + 1) +
                      ": the config must be a YAML mapping (key: value), got " + NodeKind(root));
  }
  if (!root.IsNull()) ParseMap(root, "", source, &errors, key_places);
  for (const ConfigOverride& o : overrides) ParseOverride(o, &errors, key_places);
  if (!errors.empty()) {
    std::string msg = source + ": invalid configuration";
    for (const auto& e : errors) msg += "\n  " + e;
    throw ConfigError(msg);
  }
}

std::string ConfigSchema::Dump(bool with_comments) const {
  std::ostringstream os;
  std::string open_section;
  for (const auto& e : entries_) {
    const auto dot = e.key.rfind('.');
    const std::string section = dot == std::string::npos ? "" : e.key.substr(0, dot);
    const std::string leaf = dot == std::string::npos ? e.key : e.key.substr(dot + 1);
    if (section != open_section) {
      // Only one level of sections is used by sacfuse's configs.
      if (!section.empty()) os << (open_section.empty() && os.tellp() == 0 ? "" : "\n") << section << ":\n";
      open_section = section;
    }
    const std::string indent = section.empty() ? "" : "  ";
    if (with_comments) os << indent << "# " << e.doc << "\n";
    os << indent << leaf << ": " << e.get() << "\n";
  }
  return os.str();
}

std::vector<OptionError> ConfigSchema::Check(uint32_t scopes) const {
  std::vector<OptionError> errors;
  for (const auto& e : entries_) {
    if ((e.spec.scopes & scopes) == 0) continue;
    for (OptionError& error : e.check()) errors.push_back(std::move(error));
  }
  return errors;
}

std::vector<OptionRow> ConfigSchema::Rows() const {
  std::vector<OptionRow> rows;
  rows.reserve(entries_.size());
  for (const auto& e : entries_) rows.push_back({e.key, e.type, e.get(), e.doc, e.spec});
  return rows;
}

std::vector<std::pair<std::string, std::string>> ConfigSchema::Values() const {
  std::vector<std::pair<std::string, std::string>> values;
  values.reserve(entries_.size());
  for (const auto& e : entries_) values.emplace_back(e.key, e.get());
  return values;
}

}  // namespace sacfuse
