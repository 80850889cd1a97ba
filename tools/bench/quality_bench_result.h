#pragma once
// `sacfuse bench`, part 3: the result of one row (scores, size, cost) and its JSON (OUT/rows/.../row.json, reread
// on resume, and the rows of bench.json). Scores come from the eval.json that `sacfuse eval` writes.
#include <cstdint>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

namespace sacfuse::bench {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

struct RowMetrics {
  double f1_2gsd_pct = kNoValue;            // density-normalised (primary) F1 at 2 x GSD, %
  double f1_5gsd_pct = kNoValue;            // ... at 5 x GSD, %
  double accuracy_2gsd_pct = kNoValue;      // primary accuracy at 2 x GSD, %
  double completeness_2gsd_pct = kNoValue;  // primary completeness at 2 x GSD, %
  double mean_abs_distance_m = kNoValue;    // of the observed result points at the smallest threshold
  uint64_t points = 0;                      // points of the fused cloud
  double redundancy = kNoValue;             // points in the mask per GSD^2 of mask area (Redundancy())
  double dsm_nmad_m = kNoValue;             // the run's DSM against the reference (eval.json "dsm"): NMAD, m
  double dsm_completeness_pct = kNoValue;   // ... and completeness over the mask, %
  double wall_s = kNoValue;                 // the fusion command (child process), seconds
  double peak_rss_mib = kNoValue;           // its peak resident memory, MiB
};

struct RowResult {
  std::string status = "failed";  // "ok" or "failed"
  std::string error;              // why it failed
  bool reused = false;            // read back from an earlier bench run (resume), not run now
  std::string key;                // everything the result depends on (config text, command, block); resume key
  RowMetrics metrics;
  double eval_s = kNoValue;       // scoring, seconds (not part of wall_s)
  double fusion_wall_s = kNoValue;      // sacfuse rows: run_report.json's fusion wall time (loading to LAS)
  double fusion_peak_rss_mib = kNoValue;  // ... and its peak RSS
  std::string tool_version;       // COLMAP rows: the COLMAP version that ran
  bool ok() const { return status == "ok"; }
};

// Points in the mask per reference-surface GSD cell: points_in_mask / (area_m2 / gsd_m^2); 1.0 = one point per
// GSD x GSD cell of the evaluated area. NaN when area or GSD is not positive.
double Redundancy(double points_in_mask, double area_m2, double gsd_m);

// Scores of an eval.json (EvalReportToJson) at 2 and 5 x gsd_m; also mean distance, points in the file,
// redundancy and, when it scored a DSM, the DSM's NMAD and completeness. Throws InputError (naming the file) when it cannot be read or lacks a threshold.
RowMetrics MetricsFromEvalJson(const std::string& eval_json, double gsd_m);

// Numbers as JSON; NaN becomes null (and null reads back as NaN).
nlohmann::json RowResultToJson(const RowResult& result);
RowResult RowResultFromJson(const nlohmann::json& j);

}  // namespace sacfuse::bench
