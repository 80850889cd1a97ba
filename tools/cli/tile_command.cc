// `sacfuse tile CONFIG --id ID`: computes exactly one tile of a tiled run, for running tiles as separate
// processes or on several machines sharing DIR (GNU parallel, SLURM arrays; see tools/slurm_array_example.sh).
// Idempotent and safe to run concurrently: a done tile is skipped and a tile another live worker has claimed is
// left to it (both exit 0); see jobs/tile_queue.h and tiles/tile_claim.h.
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

struct TileArgs {
  ConfigArgs config;
  std::string id;
};

int TileCommand(const TileArgs& args) {
  const JobConfig config = args.config.Load();
  SetupLogging(config.log.level, LogPath(config));
  const OutputWorkerLock lock(config);  // beside a run by design; waits out a writer's cleanup (a moment)
  const TileWorkOutcome out = RunOneTile(config, args.id, lock);
  switch (out.result) {
    case TileWork::kAlreadyDone:
      std::cout << "tile " << args.id << ": done, skipped\n";
      return kExitOk;
    case TileWork::kHeldElsewhere:
      std::cout << "tile " << args.id << ": claimed by " << out.detail << ", skipped\n";
      return kExitOk;
    case TileWork::kComputed:
      std::cout << "tile " << args.id << ": computed, " << out.fused.points_written << " points\n";
      return kExitOk;
    case TileWork::kFailed:
      std::cout << "tile " << args.id << ": failed: " << out.detail << "\n";
      return kExitFailure;
  }
  return kExitFailure;
}

}  // namespace

void AddTileCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<TileArgs>();
  auto* cmd = app.add_subcommand("tile", "Compute one tile of a tiled run (skipped when done or claimed by another "
                                         "live worker); for parallel / multi-machine runs");
  AddConfigOptions(cmd, &args->config, "YAML config of the run (with the run's --set and --output-dir)");
  cmd->add_option("--id", args->id, "Tile id such as 3_4 (see sacfuse plan CONFIG --list)")->required();
  cmd->callback([args, exit_code] {
    SetupLogging("info");
    *exit_code = RunGuarded([&] { return TileCommand(*args); });
  });
}

}  // namespace sacfuse::cli
