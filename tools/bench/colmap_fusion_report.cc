#include "tools/bench/colmap_fusion_report.h"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "io/json_text.h"

namespace sacfuse {

std::string ColmapFusionToJson(const ColmapFusionRequest& request, const ColmapFusionResult& result,
                               const ColmapFusionScoring& scoring, int indent) {
  nlohmann::json j;
  j["method"] = "colmap stereo_fusion";
  j["colmap_version"] = result.colmap_version;
  j["colmap_path"] = result.colmap_path;
  j["command"] = result.command;
  j["options"] = {{"threads", request.threads},
                  {"num_threads", request.threads > 0 ? request.threads : -1},
                  {"cache_size_gb", request.memory_gb},
                  {"use_cache", request.use_cache},
                  {"input_type", request.input_type}};
  nlohmann::json extra = nlohmann::json::object();
  for (const auto& [name, value] : request.stereo_fusion_options) extra[name] = value;
  j["options"]["stereo_fusion"] = extra;
  j["input_workspace"] = request.workspace;
  j["shifted_workspace"] = result.workspace.path;
  j["offset"] = {result.workspace.offset.x(), result.workspace.offset.y(), result.workspace.offset.z()};
  j["log"] = result.log_path;
  j["fused_ply"] = result.ply_path;
  j["fused_las"] = result.las_path;
  j["exit_code"] = result.run.exit_code;
  j["wall_s"] = result.run.wall_s;
  j["peak_rss_mib"] = result.run.peak_rss_mib;
  j["parent_rss_at_fork_mib"] = result.run.parent_rss_at_fork_mib;
  j["cpu_s"] = result.run.user_s + result.run.system_s;
  j["user_s"] = result.run.user_s;
  j["system_s"] = result.run.system_s;
  j["prepare_s"] = result.prepare_s;
  j["convert_s"] = result.convert_s;
  j["points"] = result.points;
  if (scoring.report) {
    nlohmann::json scores = nlohmann::json::array();
    for (const ThresholdScore& s : scoring.report->scores) {
      scores.push_back({{"tau_m", s.tau_m},
                        {"tau_gsd", scoring.gsd_m > 0 ? s.tau_m / scoring.gsd_m : 0.0},
                        {"f1", s.f1},
                        {"accuracy", s.accuracy},
                        {"completeness", s.completeness},
                        {"raw_f1", s.raw_f1},
                        {"raw_accuracy", s.raw_accuracy},
                        {"raw_completeness", s.raw_completeness}});
    }
    j["evaluation"] = {{"reference", scoring.reference},
                       {"gsd_m", scoring.gsd_m},
                       {"eval_json", scoring.eval_json},
                       {"mean_abs_distance_m", scoring.report->mean_abs_distance_m},
                       {"median_abs_distance_m", scoring.report->median_abs_distance_m},
                       {"scores", scores}};
  } else {
    j["evaluation"] = nullptr;
  }
  return JsonText(j, indent);
}

void WriteColmapFusionJson(const ColmapFusionRequest& request, const ColmapFusionResult& result,
                           const ColmapFusionScoring& scoring, const std::string& path) {
  WriteFileAtomically(path, ColmapFusionToJson(request, result, scoring) + "\n");
}

std::string FormatColmapFusionSummary(const ColmapFusionResult& result, const ColmapFusionScoring& scoring) {
  char line[256];
  std::string text;
  std::snprintf(line, sizeof(line), "%s stereo_fusion: %.1f s wall, %.1f s CPU, %.0f MiB peak RSS\n",
                result.colmap_version.c_str(), result.run.wall_s, result.run.user_s + result.run.system_s,
                result.run.peak_rss_mib);
  text += line;
  text += "fused cloud: " + result.las_path + " (" + std::to_string(result.points) + " points)\n";
  if (!scoring.report) {
    text += "not scored: the config sets no evaluation.reference\n";
    return text;
  }
  for (const ThresholdScore& s : scoring.report->scores) {
    std::snprintf(line, sizeof(line),
                  "COLMAP F1 @ %.3f m (%.1f x GSD): %.2f %%  (accuracy %.2f %%, completeness %.2f %%)\n", s.tau_m,
                  scoring.gsd_m > 0 ? s.tau_m / scoring.gsd_m : 0.0, 100.0 * s.f1, 100.0 * s.accuracy,
                  100.0 * s.completeness);
    text += line;
  }
  return text;
}

}  // namespace sacfuse
