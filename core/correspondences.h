#pragma once
// Point groups (paper Section III.B): for each node, its corresponding nodes in other views, at most one per
// view. Three strategies (SacOptions::correspondence), compared in the paper's Table IV.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct Correspondences {
  std::vector<uint32_t> offsets;   // nodes + 1 (CSR)
  std::vector<uint32_t> node_ids;  // corresponding node ids, ordered by the neighbour order of the node's view

  const uint32_t* begin(uint32_t node) const { return node_ids.data() + offsets[node]; }
  const uint32_t* end(uint32_t node) const { return node_ids.data() + offsets[node + 1]; }
  size_t count(uint32_t node) const { return offsets[node + 1] - offsets[node]; }
};

// The corresponding nodes of one node at a time (a node's list does not depend on any other node's), so that they
// can be found for every node (FindCorrespondences) or only for the nodes whose labels are asked for
// (NodeLabels, core/sac_labeling.h). Throws Error for the dense strategy when a view has no consistency graph. With
// `noise_factor` (core/view_noise.h, one per view; empty = none) the reprojection strategy's depth test also
// accepts depths within correspondence_tolerance_sigmas sigma of the two views' depth difference. `views`,
// `nodes`, `neighbors` and `options` must outlive the finder.
class CorrespondenceFinder {
 public:
  CorrespondenceFinder(const std::vector<SacView>& views, const NodeTable& nodes,
                       const std::vector<std::vector<uint32_t>>& neighbors, const SacOptions& options,
                       const std::vector<double>& noise_factor = {});
  ~CorrespondenceFinder();

  // The most correspondents a node can have.
  size_t stride() const { return stride_; }
  // Fills `out[0, stride())` with node `node`'s correspondents in order, kNoCorrespondent where there is none.
  void Find(uint32_t node, uint32_t* out) const;

  static constexpr uint32_t kNoCorrespondent = UINT32_MAX;

 private:
  struct ProximityIndex;
  const std::vector<SacView>& views_;
  const NodeTable& nodes_;
  const std::vector<std::vector<uint32_t>>& neighbors_;
  const SacOptions& options_;
  std::vector<double> noise_factor_;
  size_t stride_ = 1;
  std::unique_ptr<ProximityIndex> proximity_;  // the proximity strategy's k-d tree over the valid nodes
};

// Every node's correspondents. Deterministic for any thread count.
Correspondences FindCorrespondences(const CorrespondenceFinder& finder, size_t num_nodes);
Correspondences FindCorrespondences(const std::vector<SacView>& views, const NodeTable& nodes,
                                    const std::vector<std::vector<uint32_t>>& neighbors, const SacOptions& options,
                                    const std::vector<double>& noise_factor = {});

}  // namespace sacfuse
