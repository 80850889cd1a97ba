#include "tools/bench/quality_bench_result.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/error.h"

namespace sacfuse::bench {
namespace {

using nlohmann::json;

json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double NumberOf(const json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNoValue;
}

}  // namespace

double Redundancy(double points_in_mask, double area_m2, double gsd_m) {
  if (!(area_m2 > 0) || !(gsd_m > 0)) return kNoValue;
  return points_in_mask / (area_m2 / (gsd_m * gsd_m));
}

RowMetrics MetricsFromEvalJson(const std::string& eval_json, double gsd_m) {
  json j;
  try {
    std::ifstream in(eval_json);
    if (!in) throw InputError(eval_json, "cannot open the evaluation JSON");
    j = json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(eval_json, std::string("not valid JSON: ") + e.what());
  }
  RowMetrics m;
  bool have2 = false, have5 = false;
  try {
    for (const json& s : j.at("scores")) {
      const double k = s.at("tau_m").get<double>() / gsd_m;
      if (std::abs(k - 2.0) < 1e-6) {
        m.f1_2gsd_pct = 100.0 * s.at("f1").get<double>();
        m.accuracy_2gsd_pct = 100.0 * s.at("accuracy").get<double>();
        m.completeness_2gsd_pct = 100.0 * s.at("completeness").get<double>();
        have2 = true;
      } else if (std::abs(k - 5.0) < 1e-6) {
        m.f1_5gsd_pct = 100.0 * s.at("f1").get<double>();
        have5 = true;
      }
    }
    m.mean_abs_distance_m = j.at("mean_abs_distance_m").get<double>();
    const uint64_t stride = std::max<uint64_t>(1, j.value("result_stride", uint64_t{1}));
    const uint64_t scored = j.at("result_points").get<uint64_t>();
    const uint64_t in_file = j.value("result_points_in_file", uint64_t{0});
    m.points = in_file > 0 ? in_file : scored;
    const double outside = static_cast<double>(j.value("result_points_outside_mask", uint64_t{0}));
    m.redundancy = Redundancy((static_cast<double>(scored) - outside) * static_cast<double>(stride),
                              j.at("area_m2").get<double>(), gsd_m);
    if (j.contains("dsm")) {
      m.dsm_nmad_m = j.at("dsm").at("all").at("nmad_m").get<double>();
      m.dsm_completeness_pct = 100.0 * j.at("dsm").at("all").at("completeness").get<double>();
    }
  } catch (const json::exception& e) {
    throw InputError(eval_json, std::string("unexpected evaluation JSON: ") + e.what());
  }
  if (!have2 || !have5) {
    throw InputError(eval_json, "no score at 2 and 5 x GSD (" + std::to_string(gsd_m) +
                     " m); evaluation.tau_gsd must include 2 and 5");
  }
  return m;
}

json RowResultToJson(const RowResult& r) {
  const RowMetrics& m = r.metrics;
  return {{"status", r.status},
          {"error", r.error},
          {"reused", r.reused},
          {"key", r.key},
          {"f1_2gsd_pct", Number(m.f1_2gsd_pct)},
          {"f1_5gsd_pct", Number(m.f1_5gsd_pct)},
          {"accuracy_2gsd_pct", Number(m.accuracy_2gsd_pct)},
          {"completeness_2gsd_pct", Number(m.completeness_2gsd_pct)},
          {"mean_abs_distance_m", Number(m.mean_abs_distance_m)},
          {"points", m.points},
          {"redundancy", Number(m.redundancy)},
          {"dsm_nmad_m", Number(m.dsm_nmad_m)},
          {"dsm_completeness_pct", Number(m.dsm_completeness_pct)},
          {"wall_s", Number(m.wall_s)},
          {"peak_rss_mib", Number(m.peak_rss_mib)},
          {"eval_s", Number(r.eval_s)},
          {"fusion_wall_s", Number(r.fusion_wall_s)},
          {"fusion_peak_rss_mib", Number(r.fusion_peak_rss_mib)},
          {"tool_version", r.tool_version}};
}

RowResult RowResultFromJson(const json& j) {
  RowResult r;
  r.status = j.value("status", std::string("failed"));
  r.error = j.value("error", std::string());
  r.reused = j.value("reused", false);
  r.key = j.value("key", std::string());
  RowMetrics& m = r.metrics;
  m.f1_2gsd_pct = NumberOf(j, "f1_2gsd_pct");
  m.f1_5gsd_pct = NumberOf(j, "f1_5gsd_pct");
  m.accuracy_2gsd_pct = NumberOf(j, "accuracy_2gsd_pct");
  m.completeness_2gsd_pct = NumberOf(j, "completeness_2gsd_pct");
  m.mean_abs_distance_m = NumberOf(j, "mean_abs_distance_m");
  m.points = j.value("points", uint64_t{0});
  m.redundancy = NumberOf(j, "redundancy");
  m.dsm_nmad_m = NumberOf(j, "dsm_nmad_m");
  m.dsm_completeness_pct = NumberOf(j, "dsm_completeness_pct");
  m.wall_s = NumberOf(j, "wall_s");
  m.peak_rss_mib = NumberOf(j, "peak_rss_mib");
  r.eval_s = NumberOf(j, "eval_s");
  r.fusion_wall_s = NumberOf(j, "fusion_wall_s");
  r.fusion_peak_rss_mib = NumberOf(j, "fusion_peak_rss_mib");
  r.tool_version = j.value("tool_version", std::string());
  return r;
}

}  // namespace sacfuse::bench
