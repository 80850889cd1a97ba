#include "core/method_views.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/error.h"

namespace sacfuse {
namespace {

constexpr int kFootprintStridePx = 8;

}  // namespace

std::vector<uint32_t> PrecisionOrder(const std::vector<double>& sigma_rel) {
  std::vector<uint32_t> order(sigma_rel.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return sigma_rel[a] < sigma_rel[b]; });
  return order;
}

ViewPlan ViewPlanFromDepth(const std::vector<SacView>& views, const NeighborViewOptions& options) {
  std::vector<Box2d> boxes(views.size());
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
