#include "jobs/method_geometry.h"

#include <algorithm>
#include <cmath>

#include "tiling/footprint.h"

namespace sacfuse {

namespace {

// The reference height: the median of the input's scene points, or the middle of [z_min, z_max] without them.
double ReferenceHeight(const DepthBlock& input, double z_min_m, double z_max_m) {
  std::vector<double> heights = input.SceneHeights();
  if (heights.empty()) return 0.5 * (z_min_m + z_max_m);
  std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
  return heights[heights.size() / 2];
}

// A view's depth along its optical axis at height z_ref and its focal length at depth-raster resolution; false for a
// view whose principal ray does not come down to that height.
bool DepthAndFocal(const View& view, const DepthRasterSize& size, double z_ref, double* z, double* fx) {
  const Eigen::Vector3d direction = view.ViewDirectionInWorld();
  if (!(direction.z() < -1e-9)) return false;
  *z = (z_ref - view.CenterInWorld().z()) / direction.z();
  *fx = view.camera.fx * size.width / view.camera.width;
  return *z > 0 && *fx > 0;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

MethodGeometry BlockMethodGeometry(const DepthBlock& input, const std::vector<DepthRasterSize>& depth_sizes,
                                   double z_min_m, double z_max_m, const NeighborViewOptions& options) {
  const std::vector<View>& views = input.views();
  const size_t n = views.size();
  std::vector<Box2d> boxes(n);
  std::vector<Eigen::Vector3d> directions(n);
  std::vector<double> sigma(n, 1e300);
  std::vector<double> gsd;
  const double z_ref = ReferenceHeight(input, z_min_m, z_max_m);
  for (size_t v = 0; v < n; ++v) {
    const View& view = views[v];
    boxes[v] = FootprintBounds(view, z_min_m, z_max_m);
    directions[v] = view.ViewDirectionInWorld();
    double z = 0, fx = 0;
    if (DepthAndFocal(view, depth_sizes[v], z_ref, &z, &fx)) {
      sigma[v] = z * z / fx;
      gsd.push_back(z / fx);
    }
  }
  MethodGeometry out;
  out.plan.neighbors = NeighborsFromFootprints(boxes, directions, options);
  out.plan.order = PrecisionOrder(sigma);
  out.gsd_m = Median(gsd);
  return out;
}

double BlockDepthGsd(const DepthBlock& input, const std::vector<DepthRasterSize>& depth_sizes, double z_min_m,
                     double z_max_m) {
  const double z_ref = ReferenceHeight(input, z_min_m, z_max_m);
  std::vector<double> gsd;
  for (size_t v = 0; v < input.views().size(); ++v) {
    double z = 0, fx = 0;
    if (DepthAndFocal(input.views()[v], depth_sizes[v], z_ref, &z, &fx)) gsd.push_back(z / fx);
  }
  return Median(gsd);
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
