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
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/correspondences.h"
#include "core/netlets.h"
#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct LabelingStats {
  size_t labelled_nodes = 0;              // valid nodes whose label was solved (NodeLabels: asked for)
  size_t correspondences = 0;             // their correspondents, summed
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

// The labels the collapse reads (chosen_view above). With per-node Netlets and no cross-Netlet smoothness (the
// defaults) a node's Netlet depends on that node alone (its correspondents, their points, the views' depth maps),
// so it is built and solved the first time the node's label is asked for (issue 13): a tile's collapse asks only
// for the nodes its own pixels and their points' projections land in. On a full-scale Dortmund tile that is 49 %
// of the valid nodes; the rest lie in the windows' margins, which other tiles own. The labels asked for are those
// LabelNetlets gives. Otherwise (partition Netlets, smoothness rounds: a label depends on other Netlets) every
// label is solved by LabelNetlets when constructed. `views`, `nodes`, `finder` and `options` must outlive it.
class NodeLabels {
 public:
  NodeLabels(const std::vector<SacView>& views, const NodeTable& nodes, const CorrespondenceFinder& finder,
             const SacOptions& options);
  // Labels solved already (chosen_view of LabelNetlets, or made by hand in a test), with their statistics.
  explicit NodeLabels(const std::vector<uint32_t>& chosen_view, LabelingStats stats = {});

  // The view node `node`'s cluster takes its points from; solved now if it was not yet. Thread-safe.
  uint32_t At(uint32_t node) const {
    const uint32_t entry = labels_[node].load(std::memory_order_relaxed);
    return (entry & kSolved) != 0 ? entry & ~kSolved : Solve(node);
  }
  // Over the labels solved so far (all of them when not on demand).
  LabelingStats Stats() const;
  bool on_demand() const { return on_demand_; }

 private:
  static constexpr uint32_t kSolved = uint32_t{1} << 31;  // else not solved yet
  uint32_t Solve(uint32_t node) const;

  // On demand: what a node's Netlet is built and solved from.
  const std::vector<SacView>* views_ = nullptr;
  const NodeTable* nodes_ = nullptr;
  const CorrespondenceFinder* finder_ = nullptr;
  const SacOptions* options_ = nullptr;
  bool on_demand_ = false;
  LabelingStats solved_stats_;  // when not on demand
  // Per node: kSolved | label, read by the collapse's hot loops (4 bytes, as a plain label array).
  std::unique_ptr<std::atomic<uint32_t>[]> labels_;
  // On demand, per node solved: members << 16 | correspondents << 1 | proven optimal, for Stats().
  std::unique_ptr<std::atomic<uint32_t>[]> netlets_;
};

}  // namespace sacfuse
