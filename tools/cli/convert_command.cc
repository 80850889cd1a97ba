// `sacfuse convert CONFIG --to FORMAT --out DIR`: writes the config's input block in another input format
// (jobs/convert_input.h) and a config `DIR/sacfuse.yaml` that fuses the converted block with the same settings
// (output under DIR/out).
#include <filesystem>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "config/job_config.h"
#include "io/atomic_file.h"
#include "jobs/convert_input.h"
#include "jobs/open_input.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/config_args.h"

namespace sacfuse::cli {
namespace {

struct ConvertArgs {
  ConfigArgs config;
  std::string target;
  std::string out_dir;
};

int ConvertCommand(const ConvertArgs& args) {
  JobConfig config = args.config.Load();
  const std::unique_ptr<DepthBlock> input = OpenNonEmptyInput(config.input, "convert", config.crs);
  const std::string out_dir = std::filesystem::absolute(args.out_dir).lexically_normal().string();
  std::filesystem::create_directories(out_dir);
  std::cout << "converting " << input->views().size() << " views of " << input->source() << " to " << args.target
            << " in " << out_dir << "\n";
  config.input = ConvertInput(*input, args.target, out_dir, ConvertContext{config.crs});
  config.output.dir = (std::filesystem::path(out_dir) / "out").string();
  const std::string yaml_path = (std::filesystem::path(out_dir) / "sacfuse.yaml").string();
  WriteFileAtomically(yaml_path, DumpJobConfig(config, false));
  std::cout << "run it: sacfuse run " << yaml_path << "\n";
  return kExitOk;
}

}  // namespace

void AddConvertCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<ConvertArgs>();
  auto* cmd = app.add_subcommand("convert", "Write the config's input block in another input format");
  AddConfigOptions(cmd, &args->config, "YAML config whose input to convert", /*required=*/true,
                   /*output_dir=*/false);  // the converted config writes into --out/out
  std::string targets;
  for (const std::string& t : ConversionTargets()) targets += (targets.empty() ? "" : ", ") + t;
  cmd->add_option("--to", args->target, "target format: " + targets + " (see jobs/convert_input.h)")->required();
  cmd->add_option("--out", args->out_dir, "output folder")->required();
  cmd->callback([args, exit_code] {
    SetupLogging("warn");
    *exit_code = RunGuarded([&] { return ConvertCommand(*args); });
  });
}

}  // namespace sacfuse::cli
