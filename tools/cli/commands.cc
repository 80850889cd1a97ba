#include "tools/cli/commands.h"

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "config/version.h"
#include "tools/cli/cli_support.h"

namespace sacfuse::cli {
namespace {

constexpr const char* kDevelopmentGroup = "Development commands (benchmarks, comparisons, generated docs)";

// After each command's own help text: the options every command takes and the exit codes.
constexpr const char* kCommonFooter =
    "Global options (before or after the command): -v / --verbose, -q / --quiet, --log-level LEVEL; see "
    "`sacfuse --help`. Exit codes: 0 success, 1 bad input data or a failed run, 2 bad config or command line.";

// The global -v / -q / --log-level, applied before the command runs (SetConsoleLevel); one of them at most.
void AddGlobalOptions(CLI::App& app) {
  auto level = std::make_shared<std::string>();
  auto* verbose = app.add_flag("-v,--verbose", "Console: also debug messages (as --log-level debug)");
  auto* quiet = app.add_flag("-q,--quiet",
                             "Console: warnings and errors only, no progress lines (as --log-level warn); results "
                             "still go to stdout");
  auto* log_level =
      app.add_option("--log-level", *level,
                     "Console log level: trace | debug | info | warn | error | critical | off (default: each "
                     "command's own; the log file in the output folder follows log.level)")
          ->type_name("LEVEL")
          ->check(CLI::IsMember(LogLevelNames()).description(""));
  app.parse_complete_callback([level, verbose, quiet, log_level] {
    if (verbose->count() + quiet->count() + log_level->count() > 1) {
      throw CLI::ValidationError("-v, -q, --log-level", "give one of them");
    }
    if (verbose->count() > 0) SetConsoleLevel("debug");
    if (quiet->count() > 0) SetConsoleLevel("warn");
    if (!level->empty()) SetConsoleLevel(*level);
  });
  app.fallthrough();  // the global options also after the command: `sacfuse run job.yaml -q`
}

}  // namespace

int Main(int argc, char** argv) {
  CLI::App app{"sacfuse: Select-and-Combine depth-map fusion for oriented aerial image blocks.\n"
               "Run `sacfuse <command> --help` for the options of each command.",
               "sacfuse"};
  app.require_subcommand(1);
  app.set_version_flag("--version", FullVersionString(), "Print the sacfuse version and exit");
  AddGlobalOptions(app);
  int exit_code = kExitOk;
  app.group("Commands");  // inherited by the commands added next
  AddRunCommand(app, &exit_code);
  AddPlanCommand(app, &exit_code);
  AddStatusCommand(app, &exit_code);
  AddTileCommand(app, &exit_code);
  AddMergeCommand(app, &exit_code);
  AddReportCommand(app, &exit_code);
  AddSimulateCommand(app, &exit_code);
  AddEvalCommand(app, &exit_code);
  AddDsmCommand(app, &exit_code);
  AddValidateCommand(app, &exit_code);
  AddConvertCommand(app, &exit_code);
  AddVersionCommand(app, &exit_code);
  app.group(kDevelopmentGroup);
  AddBenchCommand(app, &exit_code);
  AddColmapFusionCommand(app, &exit_code);
  AddGenDocsCommand(app, &exit_code);
  for (CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    const std::string own = command->get_footer();
    command->footer(WrapText(own.empty() ? kCommonFooter : own + "\n\n" + kCommonFooter));
  }
  app.footer(WrapText(std::string("Development commands are for benchmarks and the project's own checks; users need "
                                  "the others. ") +
                      "Exit codes: 0 success, 1 bad input data or a failed run, 2 bad config or command line."));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitConfigError;
  }
  return exit_code;
}

}  // namespace sacfuse::cli
