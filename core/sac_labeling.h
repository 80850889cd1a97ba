#pragma once
// Solving the Netlets (Eq. 2): which view each node takes its points from.
//
// Unary terms (SacOptions::unary):
//  * paper:   phi_i(y) = 1 for every candidate; ties (every labelling with one shared label) go to the seed's view.
//  * quality: phi_i(k) = quality_weight * (gsd_k / min_m gsd_m - 1)         expected depth uncertainty of view k
//                      + agreement_weight * (1 - agree_k / (n - 1))        agree_k = members whose depth maps agree
//                                                                          with member k's point (pixel-accurate
//                                                                          depth test in their own view)
//                      + displacement_weight * min(|p_i - p_k| / tau, 1)   how far node i would move
//                      - smoothness_weight * (share of node i's adjacent clusters in its own view that chose view k
//                                             in the previous round; Jacobi rounds, deterministic)
//    Candidate labels are ordered by their node-independent cost (then view index), so exact ties go to the
//    better view.
// Pairwise: Potts with weight exp(-|p_i - p_j|) for members closer than tau (Eq. 3).
#include <cstdint>
#include <vector>

#include "core/netlets.h"
#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct LabelingStats {
  size_t netlets = 0;
  size_t proven_optimal = 0;              // Netlets solved with a proof of optimality
  std::vector<size_t> size_histogram;     // [members] -> Netlets
  size_t nodes_keeping_own_view = 0;
  size_t nodes_relabelled = 0;
};

// chosen_view[node] = the view whose depth map supplies that node's cluster; its own view for nodes outside any
// Netlet (invalid depth). Deterministic for any thread count.
std::vector<uint32_t> LabelNetlets(const std::vector<SacView>& views, const NodeTable& nodes, const Netlets& netlets,
                                   const SacOptions& options, LabelingStats* stats = nullptr);

}  // namespace sacfuse
