#include "core/view_neighbors.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {

std::vector<uint32_t> BestScoredViews(std::vector<std::pair<double, uint32_t>> scored, int max_views) {
  std::sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  const size_t keep = std::min<size_t>(scored.size(), static_cast<size_t>(std::max(0, max_views)));
  std::vector<uint32_t> best;
  for (size_t i = 0; i < keep; ++i) best.push_back(scored[i].second);
  return best;
}

std::vector<std::vector<uint32_t>> NeighborsFromFootprints(const std::vector<Box2d>& boxes,
                                                           const std::vector<Eigen::Vector3d>& view_directions,
                                                           const NeighborViewOptions& options) {
  const size_t n = boxes.size();
  const double cos_max = std::cos(options.max_view_angle_deg * M_PI / 180.0);
  std::vector<std::vector<uint32_t>> neighbors(n);
  for (size_t a = 0; a < n; ++a) {
    if (!boxes[a].HasArea()) continue;
    const double area_a = boxes[a].Area();
    std::vector<std::pair<double, uint32_t>> scored;
    for (size_t b = 0; b < n; ++b) {
      if (b == a || !boxes[b].HasArea()) continue;
      const double cos_angle = view_directions[a].dot(view_directions[b]);
      if (cos_angle < cos_max) continue;
      const double overlap = OverlapArea(boxes[a], boxes[b]) / area_a;
      if (overlap < options.min_footprint_overlap) continue;
      scored.emplace_back(overlap * cos_angle, static_cast<uint32_t>(b));
    }
    neighbors[a] = BestScoredViews(std::move(scored), options.max_views);
  }
  return neighbors;
}

std::vector<std::vector<uint32_t>> SelectNeighborViews(const std::vector<SacView>& views, const NodeTable& nodes,
                                                       const SacOptions& options) {
  std::vector<Box2d> boxes(views.size());
  for (const auto& node : nodes.nodes) {
    if (node.valid) boxes[node.view].Extend(node.point_in_world.head<2>());
  }
  std::vector<Eigen::Vector3d> directions(views.size());
  for (size_t v = 0; v < views.size(); ++v) directions[v] = views[v].view.ViewDirectionInWorld();
  NeighborViewOptions o;
  o.max_views = options.max_neighbor_views;
  o.max_view_angle_deg = options.max_view_angle_deg;
  o.min_footprint_overlap = options.min_footprint_overlap;
  return NeighborsFromFootprints(boxes, directions, o);
}

}  // namespace sacfuse
