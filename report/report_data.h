#pragma once
// What the HTML run report says, gathered from the files a run leaves in its output folder (never from memory
// of the run, so `sacfuse report` can rewrite the report of any finished or failed run):
//   run_report.json (points in/out per view, times, memory, SAC counts), eval.json (scores, used only when it is
//   not older than fused.las, so an old score never describes a new cloud), tiles/manifest.json, plan.json and
//   the tile markers (tiles/tile_marker.h), sacfuse.effective.yaml, and fused.las's header.
// Missing or unreadable files do not throw: the part they feed is left out and a warning names the file.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config/job_config.h"
#include "report/report_histogram.h"
#include "report/report_tile_map.h"

namespace sacfuse {

struct ReportEvalScore {
  double tau_m = 0.0;
  double accuracy = 0.0, completeness = 0.0, f1 = 0.0;  // fractions
};

struct ReportEval {
  bool present = false;  // eval.json read and current
  bool stale = false;    // eval.json exists but is older than fused.las (not shown)
  std::vector<ReportEvalScore> scores;
  double mean_abs_distance_m = 0.0, median_abs_distance_m = 0.0;
  uint64_t result_points_evaluated = 0, reference_points_evaluated = 0;
  uint64_t result_stride = 1;  // every k-th point scored
  bool aligned = false;
};

struct ReportRun {
  bool present = false;  // run_report.json read
  std::string version, method, config_path;
  uint64_t input_points = 0, output_points = 0;
  double wall_seconds = 0.0, cpu_seconds = 0.0, peak_rss_mib = 0.0;
  int threads = 0;
  double memory_budget_gib = 0.0, memory_estimate_gib = 0.0;
  double tile_size_m = 0.0;
  std::string tiling_reason;
  double superpixel_seconds = 0.0, tiles_seconds = 0.0, merge_seconds = 0.0;
  std::vector<ViewCounts> views;  // view order
  bool has_sac = false;
  uint64_t sac_nodes = 0, sac_netlets = 0, sac_nodes_relabelled = 0;
  uint64_t sac_pixels_collapsed = 0, sac_pixels_kept_uncovered = 0, sac_pixels_outliers = 0;
  std::vector<std::pair<std::string, std::string>> failed_tiles;  // id, reason
  // run_report.json "warnings": the run's warnings about its input (io/input_warnings.h), e.g. defaults that
  // replaced missing input data.
  std::vector<std::string> input_warnings;
};

struct ReportCloud {
  std::string path;         // the fused cloud (config/output_layout.h)
  std::string name;         // its file name: fused.laz or fused.las
  bool exists = false;
  uint64_t points = 0;      // header count
  double min[3] = {0, 0, 0}, max[3] = {0, 0, 0};  // header bounds
};

struct ReportData {
  std::string output_dir;
  std::string generated_at;       // local time, "YYYY-MM-DD HH:MM"
  ReportRun run;
  ReportEval eval;
  ReportCloud cloud;
  bool tiled = false;
  double tile_size_m = 0.0;
  std::vector<ReportTile> tiles;  // tiled: tiles with views, grid order
  std::string reference_path;     // evaluation.reference ("" = none)
  std::string effective_config;   // sacfuse.effective.yaml text ("" when absent)
  std::vector<std::string> warnings;
};

// Reads everything listed above from config.output.dir.
ReportData GatherReportData(const JobConfig& config);

// Parsers of the individual files (exposed for tests); each throws std::exception on malformed content.
ReportRun ParseRunReportJson(const std::string& text);
ReportEval ParseEvalJson(const std::string& text);

// Tile states of a tiled run's output folder (as `sacfuse status` sees them: the markers, checked against the
// config's result-settings hash without recomputing checksums), placed by plan.json's core bounds when present.
std::vector<ReportTile> GatherTiles(const JobConfig& config, std::vector<std::string>* warnings);

}  // namespace sacfuse
