// `sacfuse colmap-fusion CONFIG`: COLMAP's stereo_fusion on the workspace a sacfuse config names, measured (wall
// time, peak RSS of the COLMAP process) and scored with the same evaluation as `sacfuse run` (issue 4: the
// comparison with COLMAP). The work is in tools/bench/colmap_fusion.h.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "config/job_config.h"
#include "core/error.h"
#include "io/las_crs.h"
#include "tools/bench/colmap_fusion.h"
#include "tools/bench/colmap_fusion_report.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/config_args.h"
#include "eval/eval_runner.h"

namespace sacfuse::cli {
namespace {

struct ColmapFusionArgs {
  ConfigArgs config;
  std::string out_dir;  // "" = <output.dir>/colmap_fusion
  std::string colmap = "colmap";
  int threads = -1;     // -1 = resources.threads
  bool use_cache = false;
  std::vector<std::string> stereo_fusion;  // NAME=VALUE
};

int ColmapFusionCommand(const ColmapFusionArgs& args) {
  SetupLogging("info");
  return RunGuarded([&] {
    const JobConfig config = args.config.Load();
    ColmapFusionRequest request;
    request.workspace = config.input.path;
    request.out_dir = args.out_dir.empty()
                          ? (std::filesystem::path(config.output.dir) / "colmap_fusion").string()
                          : args.out_dir;
    request.colmap = args.colmap;
    request.input_type = config.input.depth_type;
    request.threads = args.threads >= 0 ? args.threads : config.resources.threads;
    request.memory_gb = config.resources.memory_gb;
    request.use_cache = args.use_cache;
    for (const std::string& option : args.stereo_fusion) {
      request.stereo_fusion_options.push_back(ParseStereoFusionOption(option));
    }
    request.las.version_minor = config.output.las_version == "1.2" ? 2 : 4;
    request.las.scale_m = config.output.scale_m;
    AddCrsToLasOptions(ParseProjectCrs(config.crs), &request.las);  // the job's CRS, as `sacfuse run` writes it
    if (config.input.origin_m.size() == 3) {
      request.origin_m = {config.input.origin_m[0], config.input.origin_m[1], config.input.origin_m[2]};
    }
    RequireColmapBinary(request.colmap);  // before any output is written
    std::filesystem::create_directories(request.out_dir);
    SetupLogging(config.log.level, (std::filesystem::path(request.out_dir) / "sacfuse.log").string());
    spdlog::info("colmap-fusion: {} -> {}", config.input.path, request.out_dir);

    const ColmapFusionResult result = RunColmapFusion(request);
    ColmapFusionScoring scoring;
    EvalReport report;
    if (!config.evaluation.reference.empty()) {
      const EvalRequest eval = EvalRequestFromConfig(  // exactly what `sacfuse run` asks for
          config, result.las_path, (std::filesystem::path(request.out_dir) / "eval.json").string());
      report = RunEvaluation(eval, std::cout);
      scoring.report = &report;
      scoring.reference = eval.reference_las;
      scoring.eval_json = eval.json_path;
      scoring.gsd_m = eval.gsd_m;
    }
    const std::string json_path = (std::filesystem::path(request.out_dir) / "colmap_fusion.json").string();
    WriteColmapFusionJson(request, result, scoring, json_path);
    std::cout << FormatColmapFusionSummary(result, scoring) << "summary written to " << json_path << "\n";
    return kExitOk;
  });
}

}  // namespace

void AddColmapFusionCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<ColmapFusionArgs>();
  auto* cmd = app.add_subcommand(
      "colmap-fusion",
      "Run COLMAP's stereo_fusion on the workspace a sacfuse config names (in a shifted local frame, so float32 "
      "keeps millimetres), measure its wall time and peak RSS, convert fused.ply to LAS and score it as `run` "
      "does. Writes DIR/fused.las, colmap.log, eval.json, colmap_fusion.json");
  AddConfigOptions(cmd, &args->config,
                   "sacfuse YAML config (input.*, output.las_version/scale_m, resources.*, evaluation.*)");
  cmd->add_option("--out", args->out_dir, "Output folder (default: <output.dir>/colmap_fusion)");
  cmd->add_option("--colmap", args->colmap, "COLMAP binary: a path or a name on PATH")->capture_default_str();
  cmd->add_option("--threads", args->threads,
                  "StereoFusion.num_threads (0 = all cores; default: resources.threads)");
  cmd->add_flag("--use-cache", args->use_cache,
                "StereoFusion.use_cache 1: keep at most resources.memory_gb of maps in memory (COLMAP 3.8 then "
                "fuses on one thread); default 0 loads every map, as COLMAP does by default");
  cmd->add_option("--stereo-fusion", args->stereo_fusion,
                  "More COLMAP StereoFusion options, NAME=VALUE, repeatable (e.g. max_normal_error=180 for "
                  "--StereoFusion.max_normal_error 180); overrides the values above");
  cmd->callback([args, exit_code] { *exit_code = ColmapFusionCommand(*args); });
}

}  // namespace sacfuse::cli
