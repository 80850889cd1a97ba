// `sacfuse status CONFIG`: the state of the last run (DIR/run_state.json: exit code 1 when it failed or was
// interrupted) and which tiles of a tiled run are done, failed or pending, from DIR/tiles/ alone (the
// manifest and the markers; no plan is built, nothing is computed, and the inputs are not re-identified: a
// changed input shows at the next run). A done tile is re-checked against its
// LAS file's size and header count and the current config's hash; --verify also recomputes the checksums.
// A pending tile that a live worker has claimed (tiles/tile_claim.h) names the worker; a run or merge writing the
// folder now (jobs/output_lock.h) is named; the fused cloud's line says whether it is the merge of the tiles now
// done, and a cloud of the other output.format left by an earlier run is named as such. --json prints the same as
// one JSON object (the schema in the command's help).
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "config/job_config.h"
#include "config/output_layout.h"
#include "config/result_settings.h"
#include "config/version.h"
#include "core/error.h"
#include "io/json_text.h"
#include "io/process_identity.h"
#include "jobs/output_lock.h"
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
  std::string writer;  // the `run` or `merge` holding DIR/sacfuse.lock now ("" when none)
  std::string tiles_dir;
  bool tiled = false;  // a tiled run has started (DIR/tiles/manifest)
  bool settings_changed = false;
  std::vector<TileStatus> tiles;  // done, then failed, then pending
  uint64_t done_points = 0;
  std::string fused_path;
  std::string fused_text;  // "merged from the 65 done tiles (written ...)", "not written yet", ...
  bool merged = false;     // the cloud is the merge of the tiles done now (untiled: it exists)
  std::string other_format_path;  // a cloud of the other output.format left by an earlier run ("" when none)
  std::string other_format;

  size_t Count(const std::string& state) const {
    size_t n = 0;
    for (const TileStatus& t : tiles) n += t.state == state;
    return n;
  }
};

// Modification time of a file in ns since the epoch; 0 when it does not exist.
int64_t FileTimeNs(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return 0;
  return static_cast<int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
}

// The fused cloud's state: whether it is the merge of the tiles now done (tiled runs: `done` of `total`, the done
// markers' finish times), and a cloud of the other output.format left by an earlier run.
void DescribeFusedCloud(const JobConfig& config, const std::string& command_words, bool tiled, size_t done,
                        size_t total, const std::vector<int64_t>& finished_unix_ns, StatusReport* r) {
  const int64_t written = FileTimeNs(r->fused_path);
  const int64_t last_done = finished_unix_ns.empty() ? 0 : *std::max_element(finished_unix_ns.begin(),
                                                                              finished_unix_ns.end());
  const size_t done_after = static_cast<size_t>(std::count_if(finished_unix_ns.begin(), finished_unix_ns.end(),
                                                              [&](int64_t t) { return t > written; }));
  std::ostringstream text;
  if (written == 0) {
    text << "not written yet";
    if (tiled && done == total) text << " (every tile is done: `sacfuse merge " << command_words << "` writes it)";
  } else if (!tiled) {
    text << "written " << UtcText(written);
    r->merged = true;
  } else if (done < total) {
    text << "written " << UtcText(written) << " by an earlier merge; " << total - done << " of " << total
         << " tiles are not done now, so it is not the merge of the present tiles";
  } else if (last_done > written) {
    text << "written " << UtcText(written) << ", before " << done_after
         << " tiles were computed again: not merged since (`sacfuse merge " << command_words << "`)";
  } else {
    text << "merged from the " << total << " done tiles (written " << UtcText(written) << ")";
    r->merged = true;
  }
  r->fused_text = text.str();
  r->other_format = config.output.format == "las" ? "laz" : "las";
  const std::string other = FusedPathOfFormat(config, r->other_format);
  if (FileTimeNs(other) != 0) r->other_format_path = other;
}

StatusReport GatherStatus(const StatusArgs& args) {
  JobConfig config = args.config.Load();
  StatusReport r;
  r.output_dir = config.output.dir;
  r.last_run = ReadRunState(config);
  r.last_run_text = DescribeRunState(config, &r.last_run_failed);
  if (const std::optional<OutputWriter> writer = LiveOutputWriter(config)) {
    r.writer = writer->pid > 0 ? DescribeOutputWriter(*writer) : std::string("a sacfuse process (starting)");
  }
  r.tiles_dir = TilesDir(config);
  r.fused_path = FusedLasPath(config);
  const std::optional<TileManifest> manifest = TileManifest::Read(r.tiles_dir);
  if (!manifest) {
    DescribeFusedCloud(config, args.config.Words(), false, 0, 0, {}, &r);
    return r;
  }
  r.tiled = true;
  // tiling.tile_size_m = 0: the size the run chose from its memory budget, as recorded in the manifest.
  if (config.tiling.tile_size_m <= 0) config.tiling.tile_size_m = manifest->tile_size_m;
  const std::string hash = ResultSettingsHash(config);
  r.settings_changed = manifest->config_hash != hash;
  std::vector<TileStatus> done, failed, pending;
  std::vector<int64_t> finished_unix_ns;  // of the done tiles' markers
  for (const std::string& id : manifest->tiles) {
    const TileCheck check = VerifyTileDone(r.tiles_dir, id, hash, args.verify);
    if (check.done) {
      done.push_back({id, "done", "", ""});
      const auto marker = ReadTileDoneMarker(r.tiles_dir, id);
      r.done_points += marker->points;
      finished_unix_ns.push_back(marker->finished_unix_ns);
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
  DescribeFusedCloud(config, args.config.Words(), true, done.size(), manifest->tiles.size(), finished_unix_ns, &r);
  return r;
}

// The fused cloud's line(s).
void PrintFusedCloud(const StatusReport& r, std::ostream& out) {
  out << std::filesystem::path(r.fused_path).filename().string() << ": " << r.fused_text << "\n";
  if (!r.other_format_path.empty()) {
    out << std::filesystem::path(r.other_format_path).filename().string()
        << ": left by an earlier run with output.format " << r.other_format
        << "; not this config's output (the next run or merge of this config removes it)\n";
  }
}

void PrintText(const StatusReport& r, std::ostream& out) {
  if (!r.last_run_text.empty()) out << r.last_run_text << "\n";
  if (!r.writer.empty()) out << "now writing " << r.output_dir << ": " << r.writer << "\n";
  if (!r.tiled) {
    out << "no tiled run has started in " << r.output_dir << " (no " << TileManifest::Path(r.tiles_dir) << ")\n";
    PrintFusedCloud(r, out);
    return;
  }
  out << r.tiles.size() << " tiles with views: " << r.Count("done") << " done (" << r.done_points << " points), "
      << r.Count("failed") << " failed, " << r.Count("pending") << " pending\n";
  if (r.settings_changed) {
    out << "the tiles were last planned for other result-affecting settings (by the last run or `sacfuse tile` "
           "worker): tiles computed with them are pending for this config\n";
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
  PrintFusedCloud(r, out);
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
          {"writing_now", r.writer.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.writer)},
          {"fused_cloud", r.fused_path},
          {"fused_cloud_state", r.fused_text},
          {"merged", r.merged},
          {"other_format_cloud", r.other_format_path.empty() ? nlohmann::json(nullptr)
                                                             : nlohmann::json(r.other_format_path)},
          {"exit_code", exit_code}};
}

int StatusCommand(const StatusArgs& args) {
  const StatusReport report = GatherStatus(args);
  // A failed or interrupted last run makes the exit code 1.
  const int exit_code = report.last_run_failed ? kExitFailure : kExitOk;
  if (args.json) {
    std::cout << JsonText(StatusJson(report, exit_code), 2) << "\n";
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
      "done_points}, tiles: a list of {id, state: done | failed | pending, reason, claimed_by}, writing_now (the "
      "`sacfuse run` or `merge` holding the output folder now, or null), fused_cloud (its path), fused_cloud_state "
      "(the text line: merged from the done tiles, not merged since, not written yet...), merged (the cloud is the "
      "merge of the tiles done now; untiled: it exists), other_format_cloud (a cloud of the other output.format "
      "left by an earlier run, or null), exit_code (as the command's: 1 when the last run failed or was "
      "interrupted).");
  cmd->callback([args, exit_code] {
    SetupLogging("warn");
    *exit_code = RunGuarded([&] { return StatusCommand(*args); });
  });
}

}  // namespace sacfuse::cli
