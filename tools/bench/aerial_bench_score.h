#pragma once
// `sacfuse bench`, aerial-bench part 2: reading its results. score.py --json-only prints one JSON line (protocol
// v2: `scores[i]` with `tau` and `f1`, `gsd`, `points_in_mask`, `density_per_m2`, `diagnostics_v2.above_top`);
// score_dsm.py prints one too (`all`: `completeness`, `median_m`, `nmad_m`, `rmse_m`);
// peers.py keeps its rows in BLOCK/peers.json (`peers[i]`: `method`, `returncode`, `wall_s`, `peak_rss_mb`,
// `score` as score.py's).
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "tools/bench/quality_bench_result.h"

namespace sacfuse::bench {

struct AerialScore {
  double f1_2gsd = kNoValue;          // protocol v2 F1 (fraction) at tau = 2 x GSD
  double f1_5gsd = kNoValue;          // ... at 5 x GSD
  double points_in_mask = kNoValue;   // result points inside the evaluation mask
  double density_per_m2 = kNoValue;   // points in the mask per m2
  double above_top = kNoValue;        // share of in-mask points in free space above the top surface (fraction)
};

// A score object; `source` names it in errors (InputError) when it lacks a field or a threshold.
AerialScore AerialScoreFromJson(const nlohmann::json& score, const std::string& source);
nlohmann::json AerialScoreToJson(const AerialScore& score);  // NaN as null; AerialScoreFromJson reads it back

// The first line of `text` that starts with '{' (score.py's JSON line; warnings may precede it), parsed.
AerialScore ParseScoreOutput(const std::string& text, const std::string& source);

// score_dsm.py's DSM accuracy over the evaluation mask ("all"): a DSM raster sampled at the mask cells' centres,
// or a cloud gridded by its own rule (p90 of the z in each mask cell).
struct AerialDsmScore {
  double completeness = kNoValue;  // share of mask cells with a value
  double median_m = kNoValue;      // of e = DSM - LiDAR top surface
  double nmad_m = kNoValue;
  double rmse_m = kNoValue;
  bool ok() const { return completeness == completeness; }
};
// score_dsm.py's JSON line (the first line of `text` starting with '{'), or our own form (AerialDsmScoreToJson).
AerialDsmScore ParseScoreDsmOutput(const std::string& text, const std::string& source);
AerialDsmScore AerialDsmScoreFromJson(const nlohmann::json& j, const std::string& source);
nlohmann::json AerialDsmScoreToJson(const AerialDsmScore& score);  // NaN as null

struct AerialPeer {
  bool ok = false;
  std::string error;                  // why the row failed
  AerialScore score;
  double wall_s = kNoValue;           // peers.py's measurement (/usr/bin/time)
  double peak_rss_mib = kNoValue;
};

// peers.json's rows by method. A row with a non-zero returncode or no score is kept as failed.
std::map<std::string, AerialPeer> ParsePeersJson(const nlohmann::json& peers, const std::string& source);

}  // namespace sacfuse::bench
