#include <filesystem>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "config/job_config.h"
#include "core/error.h"
#include "config/output_layout.h"
#include "config/version.h"
#include "jobs/output_lock.h"
#include "jobs/run_fusion.h"
#include "jobs/run_state.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/config_args.h"

namespace sacfuse::cli {
namespace {

// The paper's Fig. 4 in one line: how few views supply most of the points after fusion.
void PrintSourceViewSummary(const RunSummary& summary, std::ostream& out) {
  std::vector<std::pair<uint64_t, std::string>> per_view;
  for (const auto& v : summary.views) per_view.emplace_back(v.output_points, v.name);
  std::sort(per_view.rbegin(), per_view.rend());
  uint64_t total = 0, running = 0;
  for (const auto& [n, name] : per_view) total += n;
  size_t half = 0;
  while (half < per_view.size() && running * 2 < total) running += per_view[half++].first;
  out << "source views: " << half << " of " << per_view.size() << " views supply half of the points; top:";
  for (size_t i = 0; i < per_view.size() && i < 5; ++i) {
    char pct[32];
    std::snprintf(pct, sizeof(pct), "%.1f%%", total ? 100.0 * per_view[i].first / total : 0.0);
    out << " " << per_view[i].second << " (" << pct << ")";
  }
  out << "\n";
}

struct RunArgs {
  ConfigArgs config;
  bool print_defaults = false;
  std::string threads;  // "" = resources.threads of the config
  std::string tiles;  // comma-separated tile ids to recompute
  bool wait = false;  // wait for another run or merge of the output folder instead of refusing
};

std::vector<std::string> SplitIds(const std::string& text) {
  std::vector<std::string> ids;
  std::string id;
  for (const char c : text + ",") {
    if (c == ',') {
      if (!id.empty()) ids.push_back(id);
      id.clear();
    } else if (c != ' ') {
      id += c;
    }
  }
  return ids;
}

int ReportFailedTiles(const RunSummary& summary, const RunArgs& args) {
  std::string ids;
  std::cout << summary.failed_tiles.size() << " of " << summary.tiles_run
            << " tiles failed; the fused cloud was not merged:\n";
  for (const auto& [id, reason] : summary.failed_tiles) {
    std::cout << "  tile " << id << ": " << reason << "\n";
    ids += (ids.empty() ? "" : ",") + id;
  }
  std::cout << "rerun them with: sacfuse run " << args.config.Words() << " --tiles " << ids << "\n";
  return kExitFailure;
}

int RunCommand(const RunArgs& args) {
  if (args.print_defaults) {
    const JobConfig defaults;
    std::cout << DumpJobConfig(defaults, /*with_comments=*/true);
    return kExitOk;
  }
  SetupLogging("info");
  return RunGuarded([&] {
    if (args.config.path.empty()) throw ConfigError("sacfuse run: a CONFIG file is required (or --print-defaults)");
    ConfigArgs config_args = args.config;
    if (!args.threads.empty()) config_args.more.push_back({"resources.threads", args.threads, false, "--threads"});
    const JobConfig config = config_args.Load();
    SetupLogging(config.log.level, LogPath(config));
    // One writer per output folder (jobs/output_lock.h): refused (or waiting) before anything of DIR is touched.
    OutputWriterLock lock(config, "run", args.wait);
    spdlog::info("{}: effective configuration ({}):\n{}", FullVersionString(), args.config.path,
                 DumpJobConfig(config, false));
    // DIR/run_state.json: running now; failed (with the error) or succeeded at the end (jobs/run_state.h).
    const std::optional<RunState> previous_state = MarkRunStarted(config);
    try {
      ProgressPrinter progress;
      const RunSummary summary = RunFusionJob(config, lock, std::ref(progress), SplitIds(args.tiles));
      if (!summary.failed_tiles.empty()) {
        std::string ids;
        for (const auto& [id, reason] : summary.failed_tiles) ids += (ids.empty() ? "" : ", ") + id;
        MarkRunEnded(config, false,
                     std::to_string(summary.failed_tiles.size()) + " of " + std::to_string(summary.tiles_run) +
                         " tiles failed (" + ids + "): " + summary.failed_tiles.front().second);
        return ReportFailedTiles(summary, args);
      }
      if (summary.tiles_run > 0) {
        std::cout << "tiles: " << summary.tiles_computed << " computed, " << summary.tiles_skipped
                  << " done and skipped (of " << summary.tiles_run << ")\n";
      }
      std::cout << "fused cloud: " << summary.las_path << " (" << summary.output_points << " points, "
                << summary.views.size() << " views, method " << summary.method << ")\n";
      if (summary.dsm.written) {
        std::cout << "DSM: " << summary.dsm.path << " (" << summary.dsm.cols << " x " << summary.dsm.rows
                  << " cells of " << summary.dsm.cell_m << " m)\n";
      }
      if (summary.ortho.written) {
        std::cout << "true orthophoto: " << summary.ortho.path << " (" << summary.ortho.cells_coloured
                  << " cells coloured)\n";
      }
      PrintSourceViewSummary(summary, std::cout);
      std::cout << summary.eval_text;  // the scores (evaluation.reference), computed by the job
    } catch (const ConfigError&) {
      MarkRunRefused(config, previous_state);  // refused before anything was computed: exit 2
      throw;
    } catch (const std::exception& e) {
      MarkRunEnded(config, false, e.what());
      spdlog::error("run failed: {}", e.what());
      throw;
    }
    MarkRunEnded(config, true);
    return kExitOk;
  });
}

}  // namespace

void AddRunCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "Fuse the depth maps named by a YAML config into DIR/fused.laz (or fused.las, fused.copc.laz: "
                                        "output.format)");
  AddConfigOptions(cmd, &args->config, "YAML config (see --print-defaults)", /*required=*/false);
  cmd->add_flag("--print-defaults", args->print_defaults, "Print a complete commented config with every default");
  cmd->add_option("--threads", args->threads, "Set resources.threads (0 = all cores), as --set resources.threads=N")
      ->type_name("N");
  cmd->add_option("--tiles", args->tiles,
                  "Tiled runs: recompute these tiles (comma-separated ids such as 3_4,3_5) even when done, "
                  "then merge");
  cmd->add_flag("--wait", args->wait,
                "When another `sacfuse run` or `merge` is writing the output folder, wait for it to finish instead "
                "of refusing (exit 1)");
  cmd->callback([args, exit_code] { *exit_code = RunCommand(*args); });
}

}  // namespace sacfuse::cli
