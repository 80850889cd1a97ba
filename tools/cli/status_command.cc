// `sacfuse status CONFIG`: the state of the last run (DIR/run_state.json: exit code 1 when it failed or was
// interrupted) and which tiles of a tiled run are done, failed or pending, from DIR/tiles/ alone (the
// manifest and the markers; no plan is built, nothing is computed, and the inputs are not re-identified: a
// changed input shows at the next run). A done tile is re-checked against its
// LAS file's size and header count and the current config's hash; --verify also recomputes the checksums.
// A pending tile that a live worker has claimed (tiles/tile_claim.h) names the worker. --json prints the same as
// one JSON object (the schema in the command's help).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "config/job_config.h"
#include "config/output_layout.h"
#include "config/result_settings.h"
#include "config/version.h"
#include "core/error.h"
#include "jobs/run_state.h"
#include "tiles/tile_claim.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/config_args.h"

namespace sacfuse::cli {
namespace {

struct StatusArgs {
  ConfigArgs config;
  bool verify = false;
  bool json = false;
};

struct TileStatus {
  std::string id;
  std::string state;       // done | failed | pending
  std::string reason;      // failed: the error; pending: why it is not done
  std::string claimed_by;  // pending and claimed by a live worker: who
};

// Everything `status` reports, gathered once and printed as text or JSON.
struct StatusReport {
  std::string output_dir;
  std::optional<RunState> last_run;
  std::string last_run_text;  // DescribeRunState
  bool last_run_failed = false;
  std::string tiles_dir;
  bool tiled = false;  // a tiled run has started (DIR/tiles/manifest)
  bool settings_changed = false;
  std::vector<TileStatus> tiles;  // done, then failed, then pending
  uint64_t done_points = 0;
  std::string fused_path;
  bool merged = false;

  size_t Count(const std::string& state) const {
    size_t n = 0;
    for (const TileStatus& t : tiles) n += t.state == state;
    return n;
  }
};

StatusReport GatherStatus(const StatusArgs& args) {
  JobConfig config = args.config.Load();
  StatusReport r;
  r.output_dir = config.output.dir;
  r.last_run = ReadRunState(config);
  r.last_run_text = DescribeRunState(config, &r.last_run_failed);
  r.tiles_dir = TilesDir(config);
  r.fused_path = FusedLasPath(config);
  const bool fused_exists = std::filesystem::exists(r.fused_path);
  const std::optional<TileManifest> manifest = TileManifest::Read(r.tiles_dir);
  if (!manifest) {
    r.merged = fused_exists;
    return r;
  }
  r.tiled = true;
  // tiling.tile_size_m = 0: the size the run chose from its memory budget, as recorded in the manifest.
  if (config.tiling.tile_size_m <= 0) config.tiling.tile_size_m = manifest->tile_size_m;
  const std::string hash = ResultSettingsHash(config);
  r.settings_changed = manifest->config_hash != hash;
  std::vector<TileStatus> done, failed, pending;
  for (const std::string& id : manifest->tiles) {
    const TileCheck check = VerifyTileDone(r.tiles_dir, id, hash, args.verify);
    if (check.done) {
      done.push_back({id, "done", "", ""});
      r.done_points += ReadTileDoneMarker(r.tiles_dir, id)->points;
    } else if (const auto reason = ReadTileFailedReason(r.tiles_dir, id)) {
      failed.push_back({id, "failed", *reason, ""});
    } else {
      TileStatus t{id, "pending", check.reason, ""};
      if (TileClaimIsLive(r.tiles_dir, id, config.tiling.claim_timeout_s)) {
        const auto claim = ReadTileClaim(r.tiles_dir, id);
        t.claimed_by = claim ? DescribeClaim(*claim) : "a worker";
      }
      pending.push_back(t);
    }
  }
  for (auto* group : {&done, &failed, &pending}) r.tiles.insert(r.tiles.end(), group->begin(), group->end());
  r.merged = fused_exists && done.size() == manifest->tiles.size();
  return r;
}

void PrintText(const StatusReport& r, std::ostream& out) {
  if (!r.last_run_text.empty()) out << r.last_run_text << "\n";
  if (!r.tiled) {
    out << "no tiled run has started in " << r.output_dir << " (no " << TileManifest::Path(r.tiles_dir) << ")\n";
    return;
  }
  out << r.tiles.size() << " tiles with views: " << r.Count("done") << " done (" << r.done_points << " points), "
      << r.Count("failed") << " failed, " << r.Count("pending") << " pending\n";
  if (r.settings_changed) {
    out << "the config's result-affecting settings differ from the last run's: tiles must be recomputed\n";
  }
  for (const TileStatus& t : r.tiles) {
    if (t.state == "done") out << "done     " << t.id << "\n";
    if (t.state == "failed") out << "failed   " << t.id << ": " << t.reason << "\n";
    if (t.state == "pending") {
      out << "pending  " << t.id << " (" << t.reason;
      if (!t.claimed_by.empty()) out << "; claimed by " << t.claimed_by;
      out << ")\n";
    }
  }
  out << "fused.las: " << (r.merged ? "merged" : "not merged") << "\n";
}

nlohmann::json StatusJson(const StatusReport& r, int exit_code) {
  nlohmann::json last_run = nullptr;
  if (r.last_run) {
    const RunState& s = *r.last_run;
    // A "running" state whose process is gone was interrupted (DescribeRunState says so and counts it a failure).
    const std::string state = s.status == "running" && r.last_run_failed ? "interrupted" : s.status;
    last_run = {{"state", state},
                {"description", r.last_run_text},
                {"error", s.error},
                {"pid", s.pid},
                {"host", s.host},
                {"started_unix_ns", s.started_unix_ns},
                {"ended_unix_ns", s.ended_unix_ns},
                {"last_success_unix_ns", s.last_success_unix_ns}};
  }
  nlohmann::json tiles = nlohmann::json::array();
  for (const TileStatus& t : r.tiles) {
    tiles.push_back({{"id", t.id}, {"state", t.state}, {"reason", t.reason}, {"claimed_by", t.claimed_by}});
  }
  return {{"version", FullVersionString()},
          {"output_dir", r.output_dir},
          {"last_run", last_run},
          {"last_run_failed", r.last_run_failed},
          {"tiled", r.tiled},
          {"settings_changed", r.settings_changed},
          {"counts",
           {{"tiles", r.tiles.size()},
            {"done", r.Count("done")},
            {"failed", r.Count("failed")},
            {"pending", r.Count("pending")},
            {"done_points", r.done_points}}},
          {"tiles", tiles},
          {"fused_cloud", r.fused_path},
          {"merged", r.merged},
          {"exit_code", exit_code}};
}

int StatusCommand(const StatusArgs& args) {
  const StatusReport report = GatherStatus(args);
  // A failed or interrupted last run makes the exit code 1.
  const int exit_code = report.last_run_failed ? kExitFailure : kExitOk;
  if (args.json) {
    std::cout << StatusJson(report, exit_code).dump(2) << "\n";
  } else {
    PrintText(report, std::cout);
  }
  return exit_code;
}

}  // namespace

void AddStatusCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<StatusArgs>();
  auto* cmd = app.add_subcommand("status", "Done / failed / pending tiles of a tiled run, from DIR/tiles/ markers");
  AddConfigOptions(cmd, &args->config, "YAML config of the run (with the run's --set and --output-dir)");
  cmd->add_flag("--verify", args->verify, "Also recompute every done tile's checksum");
  cmd->add_flag("--json", args->json, "Print one JSON object (the schema below) instead of text");
  cmd->footer(
      "--json prints an object with version (this sacfuse), output_dir, last_run (null when no run has started, "
      "else {state: succeeded | failed | running | interrupted, description, error, pid, host, started_unix_ns, "
      "ended_unix_ns, last_success_unix_ns}), last_run_failed, tiled (a tiled run has started), settings_changed "
      "(the config's result-affecting settings differ from the tiles'), counts {tiles, done, failed, pending, "
      "done_points}, tiles: a list of {id, state: done | failed | pending, reason, claimed_by}, fused_cloud (its "
      "path), merged, exit_code (as the command's: 1 when the last run failed or was interrupted).");
  cmd->callback([args, exit_code] {
    SetupLogging("warn");
    *exit_code = RunGuarded([&] { return StatusCommand(*args); });
  });
}

}  // namespace sacfuse::cli
