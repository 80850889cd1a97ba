#pragma once
// Subcommands of the sacfuse binary, one file each.
namespace CLI {
class App;
}

namespace sacfuse::cli {

int Main(int argc, char** argv);

// Each adds its subcommand to `app`; when it runs, its exit code is stored in *exit_code.
void AddRunCommand(CLI::App& app, int* exit_code);
void AddSimulateCommand(CLI::App& app, int* exit_code);
void AddEvalCommand(CLI::App& app, int* exit_code);
void AddColmapFusionCommand(CLI::App& app, int* exit_code);
void AddPlanCommand(CLI::App& app, int* exit_code);
void AddStatusCommand(CLI::App& app, int* exit_code);
void AddTileCommand(CLI::App& app, int* exit_code);
void AddMergeCommand(CLI::App& app, int* exit_code);
void AddReportCommand(CLI::App& app, int* exit_code);
void AddConvertCommand(CLI::App& app, int* exit_code);
void AddVersionCommand(CLI::App& app, int* exit_code);
void AddValidateCommand(CLI::App& app, int* exit_code);
void AddBenchCommand(CLI::App& app, int* exit_code);
void AddDsmCommand(CLI::App& app, int* exit_code);
// `sacfuse gen-docs`: prints docs/configuration.md, docs/cli.md or the man page; it reads `app` (every command).
void AddGenDocsCommand(CLI::App& app, int* exit_code);

}  // namespace sacfuse::cli
