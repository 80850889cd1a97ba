#pragma once
// `sacfuse bench`, aerial-bench part 3: the table maths on finished aerial-bench rows. Per block: each row's
// points in the mask relative to Open3D TSDF's, SAC's rank among sacfuse and the peers (oracle excluded) at 2 and
// 5 x GSD, and whether SAC is half-way from the best peer to the oracle at 2 x GSD.
#include <string>
#include <vector>

#include "tools/bench/aerial_bench_score.h"
#include "tools/bench/quality_bench_result.h"

namespace sacfuse::bench {

// The rows of a block in table order: "sacfuse", then peers.py's methods.
const std::vector<std::string>& AerialMethods();
// Table label of a method ("sacfuse", "COLMAP best", "Open3D TSDF", "union", "oracle").
std::string AerialMethodLabel(const std::string& method);

struct AerialRow {
  std::string block;       // aerial block name
  std::string method;      // one of AerialMethods()
  RowResult result;        // status, error, reused, key; metrics.wall_s and metrics.peak_rss_mib
  AerialScore score;
  // DSM accuracy (score_dsm.py): `dsm` of the DSM by sacfuse's rule (sacfuse: its product DIR/dsm.tif; peers:
  // `sacfuse dsm` of their cloud on the same cells), `dsm_p90` of the cloud gridded by score_dsm.py's own rule.
  AerialDsmScore dsm, dsm_p90;
  bool is_sac() const { return method == "sacfuse"; }
  bool is_oracle() const { return method == "oracle"; }
};

// The row's points in the mask / the TSDF row's of the same block; NaN without a successful TSDF row.
double RatioToTsdf(const AerialRow& row, const std::vector<AerialRow>& rows);

struct AerialSummary {
  std::string block;
  int ranked = 0;                  // successful rows but the oracle
  int sac_rank_2gsd = 0;           // 0 = no successful sacfuse row
  int sac_rank_5gsd = 0;
  double sac_f1_2gsd = kNoValue;
  std::string best_peer;           // best successful row at 2 x GSD that is neither sacfuse nor the oracle
  double best_peer_f1_2gsd = kNoValue;
  double oracle_f1_2gsd = kNoValue;
  double gap_closed = kNoValue;    // GapClosed(SAC, best peer, oracle) at 2 x GSD
  bool half_way = false;           // gap_closed >= 0.5
  // The DSM (sacfuse's rule): sacfuse's NMAD and completeness against the best of COLMAP best and Open3D TSDF
  // (lowest NMAD, highest completeness, each over those two); ahead = lower NMAD and higher completeness than both.
  double sac_dsm_nmad_m = kNoValue, sac_dsm_completeness = kNoValue;
  double peers_best_dsm_nmad_m = kNoValue, peers_best_dsm_completeness = kNoValue;
  bool dsm_ahead = false;
};

// One summary per block, in order of first appearance.
std::vector<AerialSummary> SummariseAerial(const std::vector<AerialRow>& rows);

}  // namespace sacfuse::bench
