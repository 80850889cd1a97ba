#include "tools/cli/config_args.h"

#include <CLI/CLI.hpp>

namespace sacfuse::cli {
namespace {

// `word` as the shell reads it back: as it is when it holds only safe characters, else in single quotes.
std::string ShellWord(const std::string& word) {
  const bool safe = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                           "0123456789_-+=.,/:@%") == std::string::npos;
  if (safe) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

JobConfig ConfigArgs::Load() const {
  std::vector<ConfigOverride> overrides;
  for (const std::string& text : set) overrides.push_back(ParseSetOption(text));
  if (!output_dir.empty()) overrides.push_back({"output.dir", output_dir, /*literal=*/true, "--output-dir"});
  overrides.insert(overrides.end(), more.begin(), more.end());
  return LoadJobConfig(path, overrides);
}

std::string ConfigArgs::Words() const {
  std::string words = ShellWord(path);
  for (const std::string& text : set) words += " --set " + ShellWord(text);
  if (!output_dir.empty()) words += " --output-dir " + ShellWord(output_dir);
  return words;
}

void AddConfigOptions(CLI::App* cmd, ConfigArgs* args, const std::string& config_help, bool required,
                      bool output_dir) {
  auto* config = cmd->add_option("CONFIG", args->path, config_help);
  if (required) config->required();
  cmd->add_option("--set", args->set,
                  "Set a config key, KEY=VALUE with VALUE read as YAML (--set fusion.tau_m=1.0, --set "
                  "crs=EPSG:25832, --set evaluation.tau_gsd=[1,2]); repeatable, after the file and before "
                  "validation, recorded in sacfuse.effective.yaml and in the resume hash like the key in the file; "
                  "relative paths are relative to the current directory")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  if (!output_dir) return;
  cmd->add_option("--output-dir", args->output_dir,
                  "Use DIR as output.dir (relative to the current directory), as --set output.dir=DIR")
      ->type_name("DIR");
}

}  // namespace sacfuse::cli
