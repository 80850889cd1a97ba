#pragma once
// Neighbouring views from geometry: views whose footprints overlap and whose viewing directions are similar
// enough to see the same surfaces. Footprints are the XY boxes of each view's valid nodes (what the depth map
// actually covers), so terrain height and oblique tilt need no assumptions.
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/box2d.h"
#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

// The one rule for neighbour views, of SAC and of every comparison method: footprint boxes overlapping by at least
// min_footprint_overlap of the view's box, viewing directions within max_view_angle_deg, the best max_views by
// overlap x cos(angle), ties by index. The job fills these from fusion.max_neighbor_views,
// fusion.max_view_angle_deg and fusion.min_footprint_overlap, so every method reprojects into the same views.
// (The up to 40 views a SAC pixel consults are chosen per region instead: core/consulted_views.h.)
struct NeighborViewOptions {
  int max_views = 10;                   // per view
  double max_view_angle_deg = 65.0;     // degrees
  double min_footprint_overlap = 0.05;  // fraction of the view's footprint box, 0-1
};

// The views of `scored` (score, view) with the highest scores, at most max_views, ties to the lower view index:
// the ranking of neighbour views here and of consulted views (core/consulted_views.h).
std::vector<uint32_t> BestScoredViews(std::vector<std::pair<double, uint32_t>> scored, int max_views);

// neighbors[v] from footprint boxes (world XY; a box without area has no neighbours and is nobody's) and viewing
// directions (unit, world frame), both indexed like the views. Deterministic.
std::vector<std::vector<uint32_t>> NeighborsFromFootprints(const std::vector<Box2d>& boxes,
                                                           const std::vector<Eigen::Vector3d>& view_directions,
                                                           const NeighborViewOptions& options);

// SAC's neighbours: the rule above on the XY boxes of each view's valid nodes, with
// neighbors[v] = up to max_neighbor_views other views, best first (score = overlap fraction x cos(angle), ties by
// index). Deterministic.
std::vector<std::vector<uint32_t>> SelectNeighborViews(const std::vector<SacView>& views, const NodeTable& nodes,
                                                       const SacOptions& options);

}  // namespace sacfuse
