#include "eval/eval_report_json.h"

#include <nlohmann/json.hpp>

#include "config/version.h"
#include "io/atomic_file.h"
#include "io/json_text.h"

namespace sacfuse {

std::string EvalReportToJson(const EvalReport& r, int indent) {
  nlohmann::json j;
  j["version"] = FullVersionString();
  nlohmann::json scores = nlohmann::json::array();
  for (const ThresholdScore& s : r.scores) {
    scores.push_back({{"tau_m", s.tau_m},
                      {"accuracy", s.accuracy},
                      {"completeness", s.completeness},
                      {"f1", s.f1},
                      {"raw_accuracy", s.raw_accuracy},
                      {"raw_completeness", s.raw_completeness},
                      {"raw_f1", s.raw_f1},
                      {"result_observed", s.result_observed},
                      {"result_accurate", s.result_accurate},
                      {"reference_visible", s.reference_visible},
                      {"reference_complete", s.reference_complete},
                      {"accuracy_voxels", s.accuracy_voxels},
                      {"completeness_voxels", s.completeness_voxels}});
  }
  j["scores"] = scores;
  j["mean_abs_distance_m"] = r.mean_abs_distance_m;
  j["median_abs_distance_m"] = r.median_abs_distance_m;
  j["result_points"] = r.result_points;
  j["result_points_in_file"] = r.result_points_in_file;
  j["result_stride"] = r.result_stride;
  j["completeness_from_all_points"] = r.completeness_from_all_points;
  j["result_points_evaluated"] = r.result_points_evaluated;
  j["result_points_unobserved"] = r.result_points_unobserved;
  j["result_points_outside_mask"] = r.result_points_outside_mask;
  j["reference_points"] = r.reference_points;
  j["reference_points_evaluated"] = r.reference_points_evaluated;
  j["area_m2"] = r.area_m2;
  j["points_per_m2"] = r.points_per_m2;
  nlohmann::json hist = nlohmann::json::object();
  for (const auto& [id, count] : r.source_id_histogram) hist[std::to_string(id)] = count;
  j["source_id_histogram"] = hist;
  j["aligned"] = r.aligned;
  nlohmann::json m = nlohmann::json::array();
  for (int row = 0; row < 4; ++row) {
    m.push_back({r.alignment(row, 0), r.alignment(row, 1), r.alignment(row, 2), r.alignment(row, 3)});
  }
  j["alignment"] = m;
  if (r.dsm) {
    const auto stats = [](const DsmErrorStats& s) {
      return nlohmann::json{{"cells", s.cells},       {"cells_with_value", s.cells_with_value},
                            {"completeness", s.completeness}, {"median_m", s.median_m},
                            {"nmad_m", s.nmad_m},     {"rmse_m", s.rmse_m},
                            {"within_2gsd", s.within_2gsd}};
    };
    nlohmann::json by_class = nlohmann::json::object();
    for (const auto& [name, s] : r.dsm->by_class) by_class[name] = stats(s);
    j["dsm"] = {{"file", r.dsm->dsm_path}, {"cell_m", r.dsm->cell_m}, {"gsd_m", r.dsm->gsd_m},
                {"all", stats(r.dsm->all)}, {"by_class", by_class}};
  }
  return JsonText(j, indent);
}

void WriteEvalReportJson(const EvalReport& report, const std::string& path) {
  WriteFileAtomically(path, EvalReportToJson(report) + "\n");
}

}  // namespace sacfuse
