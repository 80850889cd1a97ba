#include "jobs/method_geometry.h"

#include <algorithm>
#include <cmath>

#include "tiling/footprint.h"

namespace sacfuse {

MethodGeometry BlockMethodGeometry(const DepthBlock& input, const std::vector<DepthRasterSize>& depth_sizes,
                                   double z_min_m, double z_max_m, const NeighborViewOptions& options) {
  const std::vector<View>& views = input.views();
  const size_t n = views.size();
  std::vector<Box2d> boxes(n);
  std::vector<Eigen::Vector3d> directions(n);
  std::vector<double> sigma(n, 1e300);
  std::vector<double> gsd;
  std::vector<double> heights = input.SceneHeights();
  double z_ref = 0.5 * (z_min_m + z_max_m);
  if (!heights.empty()) {
    std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
    z_ref = heights[heights.size() / 2];
  }
  for (size_t v = 0; v < n; ++v) {
    const View& view = views[v];
    boxes[v] = FootprintBounds(view, z_min_m, z_max_m);
    directions[v] = view.ViewDirectionInWorld();
    const Eigen::Vector3d centre = view.CenterInWorld();
    if (directions[v].z() < -1e-9) {
      const double z = (z_ref - centre.z()) / directions[v].z();  // depth along the optical axis
      const double fx = view.camera.fx * depth_sizes[v].width / view.camera.width;
      if (z > 0 && fx > 0) {
        sigma[v] = z * z / fx;
        gsd.push_back(z / fx);
      }
    }
  }
  MethodGeometry out;
  out.plan.neighbors = NeighborsFromFootprints(boxes, directions, options);
  out.plan.order = PrecisionOrder(sigma);
  if (!gsd.empty()) {
    std::nth_element(gsd.begin(), gsd.begin() + gsd.size() / 2, gsd.end());
    out.gsd_m = gsd[gsd.size() / 2];
  }
  return out;
}

ViewPlan SubsetViewPlan(const ViewPlan& block_plan, const std::vector<uint32_t>& view_ids) {
  std::vector<int64_t> local(block_plan.neighbors.size(), -1);
  for (size_t i = 0; i < view_ids.size(); ++i) local[view_ids[i]] = static_cast<int64_t>(i);
  ViewPlan out;
  out.neighbors.resize(view_ids.size());
  for (size_t i = 0; i < view_ids.size(); ++i) {
    for (const uint32_t n : block_plan.neighbors[view_ids[i]]) {
      if (local[n] >= 0) out.neighbors[i].push_back(static_cast<uint32_t>(local[n]));
    }
  }
  for (const uint32_t v : block_plan.order) {
    if (local[v] >= 0) out.order.push_back(static_cast<uint32_t>(local[v]));
  }
  return out;
}

NeighborViewOptions NeighborOptionsOf(const SacOptions& sac) {
  NeighborViewOptions o;
  o.max_views = sac.max_neighbor_views;
  o.max_view_angle_deg = sac.max_view_angle_deg;
  o.min_footprint_overlap = sac.min_footprint_overlap;
  return o;
}

}  // namespace sacfuse
