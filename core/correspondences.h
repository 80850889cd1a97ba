#pragma once
// Point groups (paper Section III.B): for each node, its corresponding nodes in other views, at most one per
// view. Three strategies (SacOptions::correspondence), compared in the paper's Table IV.
#include <cstdint>
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

// Deterministic for any thread count. Throws Error for the dense strategy when a view has no consistency graph.
// With `noise_factor` (core/view_noise.h, one per view; empty = none) the reprojection strategy's depth test also
// accepts depths within correspondence_tolerance_sigmas sigma of the two views' depth difference.
Correspondences FindCorrespondences(const std::vector<SacView>& views, const NodeTable& nodes,
                                    const std::vector<std::vector<uint32_t>>& neighbors, const SacOptions& options,
                                    const std::vector<double>& noise_factor = {});

}  // namespace sacfuse
