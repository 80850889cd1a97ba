#include "eval/eval_runner.h"

#include <cstdio>
#include <filesystem>

#include <spdlog/spdlog.h>

#include "config/output_layout.h"
#include "eval/eval.h"
#include "eval/eval_options.h"
#include "eval/eval_report_json.h"
#include "eval/ortho_accuracy.h"
#include "core/error.h"
#include "io/gdal_raster.h"

namespace sacfuse {

EvalRequest EvalRequestFromConfig(const JobConfig& config, const std::string& result_las,
                                  const std::string& json_path) {
  EvalRequest request;
  request.result_las = result_las;
  request.reference_las = config.evaluation.reference;
  request.mask_png = config.evaluation.mask;
  request.gsd_m = config.evaluation.gsd_m;
  request.tau_gsd = config.evaluation.tau_gsd;
  request.align = config.evaluation.align;
  request.json_path = json_path;
  request.max_result_points = 0.5 * config.resources.memory_gb * (1 << 30) / 72.0;
  if (DsmWanted(config)) {
    for (const std::string& dsm : {DsmPath(config), DsmVrtPath(config)}) {
      std::error_code ec;
      if (std::filesystem::is_regular_file(dsm, ec)) request.dsm = dsm;
    }
  }
  return request;
}

EvalReport RunEvaluation(const EvalRequest& request, std::ostream& out) {
  EvalOptions options;
  options.gsd_m = request.gsd_m;
  options.tau_gsd = request.tau_gsd;
  options.tau_m = request.tau_m;
  options.mask_path = request.mask_png;
  options.align = request.align;
  options.json_path = request.json_path;
  options.max_result_points = request.max_result_points;
  ValidateEvalOptions(options);
  spdlog::info("evaluating {} against {}", request.result_las, request.reference_las);
  EvalReport report = EvaluateLasFiles(request.result_las, request.reference_las, options);
  if (report.result_stride > 1) {
    out << "accuracy scored on every " << report.result_stride << "th of " << report.result_points_in_file
        << " result points (memory budget); completeness against all of them\n";
  }
  out << FormatEvalTable(report);
  for (const auto& s : report.scores) {
    char line[160];
    std::snprintf(line, sizeof(line), "F1 @ %.3f m (%.1f x GSD): %.2f %%  (accuracy %.2f %%, completeness %.2f %%)\n",
                  s.tau_m, s.tau_m / request.gsd_m, 100.0 * s.f1, 100.0 * s.accuracy, 100.0 * s.completeness);
    out << line;
  }
  if (!request.dsm.empty()) {
    DsmAccuracyRequest dsm;
    dsm.dsm_path = request.dsm;
    dsm.reference_las = request.reference_las;
    dsm.mask_png = request.mask_png;
    dsm.gsd_m = request.gsd_m;
    report.dsm = EvaluateDsm(dsm);
    out << FormatDsmAccuracy(*report.dsm);
  }
  if (request.ortho.empty() != request.ortho_reference.empty()) {
    throw ConfigError("--ortho and --ortho-reference go together");
  }
  if (!request.ortho.empty()) {
    const CellWindow window =
        RasterFile(request.ortho).window().Intersection(RasterFile(request.ortho_reference).window());
    if (window.empty()) throw InputError(request.ortho, "does not overlap " + request.ortho_reference);
    const RgbaGrid reference = ReadRgbaGrid(request.ortho_reference, window);
    out << FormatOrthoScores({ScoreOrtho("true ortho", ReadRgbaGrid(request.ortho, window), reference),
                              ScoreOrtho("point colours", PointColourOrtho(request.result_las, window), reference)});
  }
  if (!request.json_path.empty()) {
    WriteEvalReportJson(report, request.json_path);
    out << "scores written to " << request.json_path << "\n";
  }
  return report;
}

}  // namespace sacfuse
