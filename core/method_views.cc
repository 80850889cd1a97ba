#include "core/method_views.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/error.h"

namespace sacfuse {
namespace {

constexpr int kFootprintStridePx = 8;

double IntersectionArea(const FootprintBox& a, const FootprintBox& b) {
  const Eigen::Vector2d lo = a.min.cwiseMax(b.min);
  const Eigen::Vector2d hi = a.max.cwiseMin(b.max);
  if (lo.x() >= hi.x() || lo.y() >= hi.y()) return 0.0;
  return (hi - lo).prod();
}

}  // namespace

std::vector<std::vector<uint32_t>> NeighborsFromFootprints(const std::vector<FootprintBox>& boxes,
                                                           const std::vector<Eigen::Vector3d>& view_directions,
                                                           const NeighborViewOptions& options) {
  const size_t n = boxes.size();
  const double cos_max = std::cos(options.max_view_angle_deg * M_PI / 180.0);
  std::vector<std::vector<uint32_t>> neighbors(n);
  for (size_t a = 0; a < n; ++a) {
    if (boxes[a].empty()) continue;
    const double area_a = (boxes[a].max - boxes[a].min).prod();
    std::vector<std::pair<double, uint32_t>> scored;
    for (size_t b = 0; b < n; ++b) {
      if (b == a || boxes[b].empty()) continue;
      const double cos_angle = view_directions[a].dot(view_directions[b]);
      if (cos_angle < cos_max) continue;
      const double overlap = IntersectionArea(boxes[a], boxes[b]) / area_a;
      if (overlap < options.min_footprint_overlap) continue;
      scored.emplace_back(-overlap * cos_angle, static_cast<uint32_t>(b));
    }
    std::sort(scored.begin(), scored.end());
    const size_t keep = std::min<size_t>(scored.size(), static_cast<size_t>(options.max_views));
    for (size_t i = 0; i < keep; ++i) neighbors[a].push_back(scored[i].second);
  }
  return neighbors;
}

std::vector<uint32_t> PrecisionOrder(const std::vector<double>& sigma_rel) {
  std::vector<uint32_t> order(sigma_rel.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return sigma_rel[a] < sigma_rel[b]; });
  return order;
}

ViewPlan ViewPlanFromDepth(const std::vector<SacView>& views, const NeighborViewOptions& options) {
  std::vector<FootprintBox> boxes(views.size());
  std::vector<Eigen::Vector3d> directions(views.size());
  std::vector<double> sigma(views.size(), 1e300);
  for (size_t v = 0; v < views.size(); ++v) {
    const SacView& view = views[v];
    directions[v] = view.view.ViewDirectionInWorld();
    std::vector<float> depths;
    for (int row = kFootprintStridePx / 2; row < view.depth->height; row += kFootprintStridePx) {
      for (int col = kFootprintStridePx / 2; col < view.depth->width; col += kFootprintStridePx) {
        const float d = view.depth->at(row, col);
        if (!IsValidDepth(d)) continue;
        boxes[v].Extend(PixelPoint(view, row, col, d).head<2>());
        depths.push_back(d);
      }
    }
    if (!depths.empty()) {
      std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
      const double z = depths[depths.size() / 2];
      sigma[v] = z * z / view.depth_camera.fx;
    }
  }
  ViewPlan plan;
  plan.neighbors = NeighborsFromFootprints(boxes, directions, options);
  plan.order = PrecisionOrder(sigma);
  return plan;
}

void CheckViewPlan(const ViewPlan& plan, size_t num_views) {
  std::vector<char> seen(num_views, 0);
  bool ok = plan.neighbors.size() == num_views && plan.order.size() == num_views;
  for (size_t i = 0; ok && i < plan.order.size(); ++i) {
    ok = plan.order[i] < num_views && !seen[plan.order[i]];
    if (ok) seen[plan.order[i]] = 1;
  }
  for (size_t v = 0; ok && v < plan.neighbors.size(); ++v) {
    for (const uint32_t n : plan.neighbors[v]) ok = ok && n < num_views && n != v;
  }
  if (!ok) throw Error("view plan does not fit the " + std::to_string(num_views) + " views given");
}


}  // namespace sacfuse
