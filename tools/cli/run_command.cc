#include <filesystem>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "config/job_config.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "jobs/run_fusion.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/eval_runner.h"

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
  std::string config_path;
  bool print_defaults = false;
  int threads = -1;
};

int RunCommand(const RunArgs& args) {
  if (args.print_defaults) {
    const JobConfig defaults;
    std::cout << DumpJobConfig(defaults, /*with_comments=*/true);
    return kExitOk;
  }
  SetupLogging("info");
  return RunGuarded([&] {
    if (args.config_path.empty()) throw ConfigError("sacfuse run: a CONFIG file is required (or --print-defaults)");
    JobConfig config = LoadJobConfig(args.config_path);
    if (args.threads >= 0) config.resources.threads = args.threads;
    SetupLogging(config.log.level, (std::filesystem::path(config.output.dir) / "sacfuse.log").string());
    spdlog::info("effective configuration ({}):\n{}", args.config_path, DumpJobConfig(config, false));
    ProgressPrinter progress;
    const RunSummary summary = RunFusionJob(config, std::ref(progress));
    std::cout << "fused cloud: " << summary.las_path << " (" << summary.output_points << " points, "
              << summary.views.size() << " views, method " << summary.method << ")\n";
    PrintSourceViewSummary(summary, std::cout);
    if (!config.evaluation.reference.empty()) {
      EvalRequest request;
      request.result_las = summary.las_path;
      request.reference_las = config.evaluation.reference;
      request.mask_png = config.evaluation.mask;
      request.gsd_m = config.evaluation.gsd_m;
      request.tau_gsd = config.evaluation.tau_gsd;
      request.align = config.evaluation.align;
      request.json_path = (std::filesystem::path(config.output.dir) / "eval.json").string();
      RunEvaluation(request, std::cout);
    }
    return kExitOk;
  });
}

}  // namespace

void AddRunCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "Fuse the depth maps named by a YAML config into DIR/fused.las");
  cmd->add_option("CONFIG", args->config_path, "YAML config (see --print-defaults)");
  cmd->add_flag("--print-defaults", args->print_defaults, "Print a complete commented config with every default");
  cmd->add_option("--threads", args->threads, "Override resources.threads (0 = all cores)");
  cmd->callback([args, exit_code] { *exit_code = RunCommand(*args); });
}

}  // namespace sacfuse::cli
