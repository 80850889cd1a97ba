// `sacfuse merge CONFIG`: merges the tiles of a tiled run into DIR/fused.las once every tile with views is done
// (exit 1 listing the missing tiles otherwise); the last step after `sacfuse tile` workers.
#include <filesystem>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "config/job_config.h"
#include "config/output_layout.h"
#include "jobs/output_lock.h"
#include "jobs/tile_queue.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/config_args.h"

namespace sacfuse::cli {
namespace {

int MergeCommand(const ConfigArgs& args, bool wait) {
  const JobConfig config = args.Load();
  SetupLogging(config.log.level, LogPath(config));
  OutputWriterLock lock(config, "merge", wait);  // one writer per output folder (jobs/output_lock.h)
  const MergeJobOutcome out = MergeJob(config, lock);
  if (!out.missing.empty()) {
    std::cout << out.missing.size() << " tiles are not done; nothing merged. Missing:";
    for (const auto& id : out.missing) std::cout << " " << id;
    std::cout << "\ncompute them with `sacfuse tile " << args.Words() << " --id ID` or `sacfuse run "
              << args.Words() << "`\n";
    return kExitFailure;
  }
  std::cout << "fused cloud: " << out.fused_las_path << " (" << out.merged.points << " points)\n";
  if (out.dsm.written) {
    std::cout << "DSM: " << out.dsm.path << " (" << out.dsm.cols << " x " << out.dsm.rows << " cells of "
              << out.dsm.cell_m << " m)\n";
  }
  if (out.ortho.written) {
    std::cout << "true orthophoto: " << out.ortho.path << " (" << out.ortho.cells_coloured << " cells coloured)\n";
  }
  return kExitOk;
}

}  // namespace

void AddMergeCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<ConfigArgs>();
  auto wait = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("merge", "Merge the done tiles of a tiled run into DIR/fused.laz (or .las, .copc.laz: output.format) and "
                                          "index them in DIR/tiles.vpc (exit 1 listing the missing tiles when some "
                                          "are not done)");
  AddConfigOptions(cmd, args.get(), "YAML config of the run (with the run's --set and --output-dir)");
  cmd->add_flag("--wait", *wait,
                "When a `sacfuse run` or another merge is writing the output folder, wait for it to finish instead "
                "of refusing (exit 1)");
  cmd->callback([args, wait, exit_code] {
    SetupLogging("info");
    *exit_code = RunGuarded([&] { return MergeCommand(*args, *wait); });
  });
}

}  // namespace sacfuse::cli
