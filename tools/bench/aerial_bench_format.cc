#include "tools/bench/aerial_bench_format.h"

#include <cmath>
#include <sstream>

#include "tools/bench/quality_bench_format.h"

namespace sacfuse::bench {
namespace {

using nlohmann::json;

json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string RowLine(const AerialRow& r, const std::vector<AerialRow>& rows) {
  std::string name = r.is_sac() ? "**sacfuse**" : AerialMethodLabel(r.method);
  if (r.result.reused) name += " ↺";
  std::string line = "| " + r.block + " | " + name + " | ";
  if (!r.result.ok()) return line + "failed | | | | | | | | | | |\n";
  const AerialScore& s = r.score;
  const auto dsm = [](const AerialDsmScore& d) {
    return d.ok() ? FormatFixed(d.nmad_m, 3) + " | " + FormatFixed(100.0 * d.completeness, 2) : std::string(" | ");
  };
  return line + FormatFixed(s.f1_2gsd, 4) + " | " + FormatFixed(s.f1_5gsd, 4) + " | " + dsm(r.dsm) + " | " +
         dsm(r.dsm_p90) + " | " + FormatFixed(s.density_per_m2, 1) + " | " + FormatFixed(RatioToTsdf(r, rows), 2) +
         " | " + FormatFixed(100.0 * s.above_top, 2) + " | " + FormatFixed(r.result.metrics.wall_s, 1) + " | " +
         FormatFixed(r.result.metrics.peak_rss_mib, 0) + " |\n";
}

std::string SummaryLine(const AerialSummary& s) {
  std::string out = "- " + s.block + ": ";
  if (s.sac_rank_2gsd == 0) return out + "no successful sacfuse row.\n";
  out += "SAC rank " + std::to_string(s.sac_rank_2gsd) + " of " + std::to_string(s.ranked) + " at 2×GSD, " +
         std::to_string(s.sac_rank_5gsd) + " of " + std::to_string(s.ranked) + " at 5×GSD; half-way to the oracle " +
         "at 2×GSD: " + (s.half_way ? "reached" : "not reached");
  if (std::isfinite(s.gap_closed)) {
    out += " (gap closed " + FormatFixed(100.0 * s.gap_closed, 1) + " %: best peer " +
           AerialMethodLabel(s.best_peer) + " " + FormatFixed(s.best_peer_f1_2gsd, 4) + ", oracle " +
           FormatFixed(s.oracle_f1_2gsd, 4) + ", SAC " + FormatFixed(s.sac_f1_2gsd, 4) + ")";
  }
  out += ".";
  if (std::isfinite(s.sac_dsm_nmad_m) && std::isfinite(s.peers_best_dsm_nmad_m)) {
    out += " DSM: NMAD " + FormatFixed(s.sac_dsm_nmad_m, 3) + " m (best peer " + FormatFixed(s.peers_best_dsm_nmad_m, 3) +
           "), completeness " + FormatFixed(100.0 * s.sac_dsm_completeness, 2) + " % (best peer " +
           FormatFixed(100.0 * s.peers_best_dsm_completeness, 2) + "): " + (s.dsm_ahead ? "ahead on both" : "NOT ahead on both") + ".";
  }
  return out + "\n";
}

}  // namespace

std::string FormatAerialMarkdown(const std::vector<AerialRow>& rows, const std::vector<AerialSummary>& summaries) {
  if (rows.empty()) return "";
  std::ostringstream md;
  md << "\n## aerial-bench (independent simulator, peers and scorer: ../shared/aerial-bench)\n\n"
     << "| block | method | F1 2×GSD | F1 5×GSD | DSM NMAD m | DSM compl. % | p90 NMAD m | p90 compl. % | points in "
        "mask /m² | × TSDF's points | above top % | wall s | peak RSS MiB |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const AerialRow& r : rows) md << RowLine(r, rows);
  md << "\n";
  for (const AerialSummary& s : summaries) md << SummaryLine(s);
  md << "\nF1: score.py protocol v2 (fractions). × TSDF's points: points in the mask / Open3D TSDF's. Above top: "
        "share of the points in the mask in free space above the top surface (`diagnostics_v2.above_top`). Rank: "
        "among the successful rows but the oracle. Half-way: (F1_SAC − F1_best peer) / (F1_oracle − F1_best peer) "
        "≥ 0.5 at 2×GSD. Wall s and peak RSS: `sacfuse run` as a child process (wait4); peers: peers.py's "
        "measurement. DSM: score_dsm.py over the mask (NMAD of DSM − LiDAR top surface, completeness = share of "
        "mask cells with a value) of the DSM by sacfuse's rule (sacfuse: its dsm.tif; COLMAP best and Open3D TSDF: "
        "`sacfuse dsm` of their cloud on the same cells); p90: the cloud gridded by score_dsm.py's own rule (p90 "
        "of z per mask cell, no hole filling).\n";
  return md.str();
}

json AerialRowsToJson(const std::vector<AerialRow>& rows) {
  json out = json::array();
  for (const AerialRow& r : rows) {
    json row = RowResultToJson(r.result);
    // Columns of our own scorer that aerial-bench rows do not have (their scores are in "aerial").
    for (const char* k : {"key", "accuracy_2gsd_pct", "completeness_2gsd_pct", "mean_abs_distance_m", "points",
                          "redundancy", "fusion_wall_s", "fusion_peak_rss_mib", "tool_version"}) {
      row.erase(k);
    }
    row["block"] = r.block;
    row["method"] = r.method;
    row["aerial"] = AerialScoreToJson(r.score);
    row["aerial_dsm"] = AerialDsmScoreToJson(r.dsm);
    row["aerial_dsm_p90"] = AerialDsmScoreToJson(r.dsm_p90);
    row["ratio_to_tsdf_points"] = Number(RatioToTsdf(r, rows));
    out.push_back(row);
  }
  return out;
}

json AerialSummariesToJson(const std::vector<AerialSummary>& summaries) {
  json out = json::array();
  for (const AerialSummary& s : summaries) {
    out.push_back({{"block", s.block}, {"ranked", s.ranked}, {"sac_rank_2gsd", s.sac_rank_2gsd},
                   {"sac_rank_5gsd", s.sac_rank_5gsd}, {"sac_f1_2gsd", Number(s.sac_f1_2gsd)},
                   {"best_peer", s.best_peer}, {"best_peer_f1_2gsd", Number(s.best_peer_f1_2gsd)},
                   {"oracle_f1_2gsd", Number(s.oracle_f1_2gsd)}, {"gap_closed", Number(s.gap_closed)},
                   {"half_way", s.half_way}, {"sac_dsm_nmad_m", Number(s.sac_dsm_nmad_m)},
                   {"sac_dsm_completeness", Number(s.sac_dsm_completeness)},
                   {"peers_best_dsm_nmad_m", Number(s.peers_best_dsm_nmad_m)},
                   {"peers_best_dsm_completeness", Number(s.peers_best_dsm_completeness)},
                   {"dsm_ahead", s.dsm_ahead}});
  }
  return out;
}

}  // namespace sacfuse::bench
