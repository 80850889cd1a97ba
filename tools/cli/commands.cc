#include "tools/cli/commands.h"

#include <CLI/CLI.hpp>

#include "tools/cli/cli_support.h"

namespace sacfuse::cli {

int Main(int argc, char** argv) {
  CLI::App app{"sacfuse: Select-and-Combine depth-map fusion for oriented aerial image blocks.\n"
               "Run `sacfuse <command> --help` for the options of each command."};
  app.require_subcommand(1);
  int exit_code = kExitOk;
  AddRunCommand(app, &exit_code);
  AddPlanCommand(app, &exit_code);
  AddStatusCommand(app, &exit_code);
  AddTileCommand(app, &exit_code);
  AddMergeCommand(app, &exit_code);
  AddReportCommand(app, &exit_code);
  AddSimulateCommand(app, &exit_code);
  AddEvalCommand(app, &exit_code);
  AddDsmCommand(app, &exit_code);
  AddColmapFusionCommand(app, &exit_code);
  AddBenchCommand(app, &exit_code);
  AddConvertCommand(app, &exit_code);
  AddValidateCommand(app, &exit_code);
  AddVersionCommand(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitConfigError;
  }
  return exit_code;
}

}  // namespace sacfuse::cli
