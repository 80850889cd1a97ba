// `sacfuse report CONFIG [--out DIR] [--no-before]`: (re)writes the HTML report of a finished (or failed) run from
// the files in its output folder: DIR/report/index.html and its pictures (report/report_writer.h). --out writes it
// elsewhere, e.g. for a run folder that is read-only. Prints the page's path, the time taken and the peak RSS.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "config/job_config.h"
#include "core/error.h"
#include "jobs/auto_tiling.h"
#include "jobs/output_lock.h"
#include "jobs/thread_limit.h"
#include "jobs/job_report.h"
#include "report/report_writer.h"
#include "jobs/run_state.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/config_args.h"

namespace sacfuse::cli {
namespace {

struct ReportArgs {
  ConfigArgs config;
  std::string out_dir;
  bool no_before = false;
};

int ReportCommand(const ReportArgs& args) {
  const JobConfig config = args.config.Load();
  if (!std::filesystem::is_directory(config.output.dir)) {
    throw InputError(config.output.dir, "no run output here (output.dir of " + args.config.path + "); run it first");
  }
  const OutputWorkerLock lock(config);  // writes DIR/report beside a run (jobs/output_lock.h)
  const ThreadLimit thread_limit(EffectiveThreads(config));  // resources.threads, as the run's report
  ReportOptions options = JobReportOptions(config);  // the input opened from config.input when needed
  options.report_dir = args.out_dir;
  options.before_profile = !args.no_before;
  const ReportFigures figures = WriteHtmlReport(config, options);
  const std::string page = (std::filesystem::path(ReportDir(config, options)) / "index.html").string();
  std::printf("report: %s (%.1f s: map %.1f s, cross-section %.1f s; peak RSS %.0f MiB)\n", page.c_str(),
              figures.seconds, figures.map_seconds, figures.profile_seconds, figures.peak_rss_mib);
  if (!figures.map.present) std::cout << "no map: " << figures.profile.reason << "\n";
  const std::string run_state = DescribeRunState(config);
  if (!run_state.empty()) std::cout << run_state << "\n";
  return kExitOk;
}

}  // namespace

void AddReportCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<ReportArgs>();
  auto* cmd = app.add_subcommand("report", "(Re)write the HTML report of a run: DIR/report/index.html with the "
                                           "source-view map, points per view, a cross-section, tiles and scores");
  AddConfigOptions(cmd, &args->config, "YAML config of the run (with the run's --set and --output-dir)");
  cmd->add_option("--out", args->out_dir, "Write the report into this folder instead of DIR/report");
  cmd->add_flag("--no-before", args->no_before,
                "Skip the 'before fusion' cross-section (it reads the input's depth windows under the strip)");
  cmd->callback([args, exit_code] {
    SetupLogging("warn");
    *exit_code = RunGuarded([&] { return ReportCommand(*args); });
  });
}

}  // namespace sacfuse::cli
