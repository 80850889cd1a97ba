// `sacfuse status CONFIG`: the state of the last run (DIR/run_state.json: exit code 1 when it failed or was
// interrupted) and which tiles of a tiled run are done, failed or pending, from DIR/tiles/ alone (the
// manifest and the markers; no plan is built, nothing is computed, and the inputs are not re-identified: a
// changed input shows at the next run). A done tile is re-checked against its
// LAS file's size and header count and the current config's hash; --verify also recomputes the checksums.
// A pending tile that a live worker has claimed (tiles/tile_claim.h) names the worker.
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include <CLI/CLI.hpp>

#include "config/job_config.h"
#include "config/result_settings.h"
#include "core/error.h"
#include "config/output_layout.h"
#include "jobs/run_state.h"
#include "tiles/tile_claim.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"

namespace sacfuse::cli {
namespace {

struct StatusArgs {
  std::string config_path;
  bool verify = false;
};

int StatusCommand(const StatusArgs& args) {
  JobConfig config = LoadJobConfig(args.config_path);
  // The last run's state first (DIR/run_state.json); a failed or interrupted run makes the exit code 1.
  bool last_run_failed = false;
  const std::string run_state = DescribeRunState(config, &last_run_failed);
  if (!run_state.empty()) std::cout << run_state << "\n";
  const int exit_code = last_run_failed ? kExitFailure : kExitOk;
  const std::string tiles_dir = TilesDir(config);
  const std::optional<TileManifest> manifest = TileManifest::Read(tiles_dir);
  if (!manifest) {
    std::cout << "no tiled run has started in " << config.output.dir << " (no " << TileManifest::Path(tiles_dir)
              << ")\n";
    return exit_code;
  }
  // tiling.tile_size_m = 0: the size the run chose from its memory budget, as recorded in the manifest.
  if (config.tiling.tile_size_m <= 0) config.tiling.tile_size_m = manifest->tile_size_m;
  const std::string hash = ResultSettingsHash(config);
  std::vector<std::string> done, failed, pending;
  std::vector<std::string> failed_reasons, pending_reasons;
  uint64_t done_points = 0;
  for (const std::string& id : manifest->tiles) {
    const TileCheck check = VerifyTileDone(tiles_dir, id, hash, args.verify);
    if (check.done) {
      done.push_back(id);
      done_points += ReadTileDoneMarker(tiles_dir, id)->points;
    } else if (const auto reason = ReadTileFailedReason(tiles_dir, id)) {
      failed.push_back(id);
      failed_reasons.push_back(*reason);
    } else {
      pending.push_back(id);
      pending_reasons.push_back(check.reason);
    }
  }
  const size_t total = manifest->tiles.size();
  std::cout << total << " tiles with views: " << done.size() << " done (" << done_points << " points), "
            << failed.size() << " failed, " << pending.size() << " pending\n";
  if (manifest->config_hash != hash) {
    std::cout << "the config's result-affecting settings differ from the last run's: tiles must be recomputed\n";
  }
  for (const auto& id : done) std::cout << "done     " << id << "\n";
  for (size_t i = 0; i < failed.size(); ++i) std::cout << "failed   " << failed[i] << ": " << failed_reasons[i] << "\n";
  for (size_t i = 0; i < pending.size(); ++i) {
    std::cout << "pending  " << pending[i] << " (" << pending_reasons[i];
    if (TileClaimIsLive(tiles_dir, pending[i], config.tiling.claim_timeout_s)) {
      const auto claim = ReadTileClaim(tiles_dir, pending[i]);
      std::cout << "; claimed by " << (claim ? DescribeClaim(*claim) : "a worker");
    }
    std::cout << ")\n";
  }
  const bool merged = std::filesystem::exists(FusedLasPath(config));
  std::cout << "fused.las: " << (merged && done.size() == total ? "merged" : "not merged") << "\n";
  return exit_code;
}

}  // namespace

void AddStatusCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<StatusArgs>();
  auto* cmd = app.add_subcommand("status", "Done / failed / pending tiles of a tiled run, from DIR/tiles/ markers");
  cmd->add_option("CONFIG", args->config_path, "YAML config of the run")->required();
  cmd->add_flag("--verify", args->verify, "Also recompute every done tile's checksum");
  cmd->callback([args, exit_code] {
    SetupLogging("warn");
    *exit_code = RunGuarded([&] { return StatusCommand(*args); });
  });
}

}  // namespace sacfuse::cli
