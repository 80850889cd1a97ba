#pragma once
// Neighbouring views from geometry: views whose footprints overlap and whose viewing directions are similar
// enough to see the same surfaces. Footprints are the XY boxes of each view's valid nodes (what the depth map
// actually covers), so terrain height and oblique tilt need no assumptions.
#include <cstdint>
#include <vector>

#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

// neighbors[v] = up to max_neighbor_views other views, best first (score = overlap fraction x cos(angle), ties by
// index). Deterministic.
std::vector<std::vector<uint32_t>> SelectNeighborViews(const std::vector<SacView>& views, const NodeTable& nodes,
                                                       const SacOptions& options);

}  // namespace sacfuse
