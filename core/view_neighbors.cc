#include "core/view_neighbors.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {
namespace {

struct Box {
  Eigen::Vector2d min = Eigen::Vector2d::Constant(1e300);
  Eigen::Vector2d max = Eigen::Vector2d::Constant(-1e300);
  bool empty() const { return min.x() > max.x(); }
  double area() const { return empty() ? 0.0 : (max - min).prod(); }
};

double IntersectionArea(const Box& a, const Box& b) {
  const Eigen::Vector2d lo = a.min.cwiseMax(b.min);
  const Eigen::Vector2d hi = a.max.cwiseMin(b.max);
  if (lo.x() >= hi.x() || lo.y() >= hi.y()) return 0.0;
  return (hi - lo).prod();
}

}  // namespace

std::vector<std::vector<uint32_t>> SelectNeighborViews(const std::vector<SacView>& views, const NodeTable& nodes,
                                                       const SacOptions& options) {
  const size_t n = views.size();
  std::vector<Box> boxes(n);
  for (const auto& node : nodes.nodes) {
    if (!node.valid) continue;
    boxes[node.view].min = boxes[node.view].min.cwiseMin(node.point_in_world.head<2>());
    boxes[node.view].max = boxes[node.view].max.cwiseMax(node.point_in_world.head<2>());
  }
  const double cos_max = std::cos(options.max_view_angle_deg * M_PI / 180.0);
  std::vector<std::vector<uint32_t>> neighbors(n);
  for (size_t a = 0; a < n; ++a) {
    if (boxes[a].area() <= 0) continue;
    const Eigen::Vector3d dir_a = views[a].view.ViewDirectionInWorld();
    std::vector<std::pair<double, uint32_t>> scored;
    for (size_t b = 0; b < n; ++b) {
      if (b == a || boxes[b].area() <= 0) continue;
      const double cos_angle = dir_a.dot(views[b].view.ViewDirectionInWorld());
      if (cos_angle < cos_max) continue;
      const double overlap = IntersectionArea(boxes[a], boxes[b]) / boxes[a].area();
      if (overlap < options.min_footprint_overlap) continue;
      scored.emplace_back(-overlap * cos_angle, static_cast<uint32_t>(b));
    }
    std::sort(scored.begin(), scored.end());
    const size_t keep = std::min<size_t>(scored.size(), options.max_neighbor_views);
    for (size_t i = 0; i < keep; ++i) neighbors[a].push_back(scored[i].second);
  }
  return neighbors;
}

}  // namespace sacfuse
