#include "tools/bench/aerial_bench_table.h"

#include <algorithm>
#include <cmath>

#include "tools/bench/quality_bench_table.h"

namespace sacfuse::bench {
namespace {

AerialSummary SummariseBlock(const std::string& block, const std::vector<AerialRow>& rows) {
  AerialSummary s;
  s.block = block;
  std::vector<double> f1_2, f1_5;
  const AerialRow* sac = nullptr;
  for (const AerialRow& r : rows) {
    if (r.block != block || !r.result.ok()) continue;
    if (r.is_oracle()) {
      s.oracle_f1_2gsd = r.score.f1_2gsd;
      continue;
    }
    f1_2.push_back(r.score.f1_2gsd);
    f1_5.push_back(r.score.f1_5gsd);
    if (r.is_sac()) {
      sac = &r;
    } else if (!(s.best_peer_f1_2gsd >= r.score.f1_2gsd)) {
      s.best_peer = r.method;
      s.best_peer_f1_2gsd = r.score.f1_2gsd;
    }
  }
  s.ranked = static_cast<int>(f1_2.size());
  if (sac == nullptr) return s;
  s.sac_dsm_nmad_m = sac->dsm.nmad_m;
  s.sac_dsm_completeness = sac->dsm.completeness;
  int peers_with_dsm = 0;
  for (const AerialRow& r : rows) {
    if (r.block != block || !r.result.ok() || (r.method != "colmap_best" && r.method != "tsdf") || !r.dsm.ok()) continue;
    ++peers_with_dsm;
    if (!(s.peers_best_dsm_nmad_m <= r.dsm.nmad_m)) s.peers_best_dsm_nmad_m = r.dsm.nmad_m;
    if (!(s.peers_best_dsm_completeness >= r.dsm.completeness)) s.peers_best_dsm_completeness = r.dsm.completeness;
  }
  s.dsm_ahead = peers_with_dsm > 0 && sac->dsm.ok() && s.sac_dsm_nmad_m < s.peers_best_dsm_nmad_m &&
                s.sac_dsm_completeness > s.peers_best_dsm_completeness;
  s.sac_f1_2gsd = sac->score.f1_2gsd;
  s.sac_rank_2gsd = RankOf(sac->score.f1_2gsd, f1_2);
  s.sac_rank_5gsd = RankOf(sac->score.f1_5gsd, f1_5);
  s.gap_closed = GapClosed(s.sac_f1_2gsd, s.best_peer_f1_2gsd, s.oracle_f1_2gsd);
  s.half_way = std::isfinite(s.gap_closed) && s.gap_closed >= 0.5;
  return s;
}

}  // namespace

const std::vector<std::string>& AerialMethods() {
  static const std::vector<std::string> methods = {"sacfuse", "colmap_best", "tsdf", "union", "oracle"};
  return methods;
}

std::string AerialMethodLabel(const std::string& method) {
  if (method == "colmap_best") return "COLMAP best";
  if (method == "tsdf") return "Open3D TSDF";
  return method;
}

double RatioToTsdf(const AerialRow& row, const std::vector<AerialRow>& rows) {
  for (const AerialRow& r : rows) {
    if (r.block == row.block && r.method == "tsdf" && r.result.ok() && r.score.points_in_mask > 0) {
      return row.score.points_in_mask / r.score.points_in_mask;
    }
  }
  return kNoValue;
}

std::vector<AerialSummary> SummariseAerial(const std::vector<AerialRow>& rows) {
  std::vector<AerialSummary> out;
  for (const AerialRow& r : rows) {
    if (std::none_of(out.begin(), out.end(), [&](const AerialSummary& s) { return s.block == r.block; })) {
      out.push_back(SummariseBlock(r.block, rows));
    }
  }
  return out;
}

}  // namespace sacfuse::bench
