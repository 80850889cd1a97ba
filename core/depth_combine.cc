#include "core/depth_combine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sacfuse {

bool SampleDepth(const DepthMap& depth, double u, double v, double max_spread_m, double* depth_m) {
  if (!(u >= 0 && v >= 0 && u < depth.width && v < depth.height)) return false;
  // Bilinear between the four pixel centres around (u, v).
  const double x = u - 0.5, y = v - 0.5;
  const int c0 = static_cast<int>(std::floor(x)), r0 = static_cast<int>(std::floor(y));
  if (c0 >= 0 && r0 >= 0 && c0 + 1 < depth.width && r0 + 1 < depth.height) {
    const float d00 = depth.at(r0, c0), d01 = depth.at(r0, c0 + 1);
    const float d10 = depth.at(r0 + 1, c0), d11 = depth.at(r0 + 1, c0 + 1);
    if (IsValidDepth(d00) && IsValidDepth(d01) && IsValidDepth(d10) && IsValidDepth(d11)) {
      const float lo = std::min(std::min(d00, d01), std::min(d10, d11));
      const float hi = std::max(std::max(d00, d01), std::max(d10, d11));
      if (hi - lo <= max_spread_m) {
        const double fx = x - c0, fy = y - r0;
        *depth_m = (1 - fy) * ((1 - fx) * d00 + fx * d01) + fy * ((1 - fx) * d10 + fx * d11);
        return true;
      }
    }
  }
  // Else the pixel holding (u, v), or where it is invalid the nearest valid one of those centres: a surface one
  // pixel away is still the view's surface there, where a lone invalid pixel would drop the view.
  const float holding = depth.at(static_cast<int>(v), static_cast<int>(u));
  if (IsValidDepth(holding)) {
    *depth_m = holding;
    return true;
  }
  bool found = false;
  double nearest_sq = 0.0;
  for (int r = std::max(0, r0); r <= std::min(depth.height - 1, r0 + 1); ++r) {
    for (int c = std::max(0, c0); c <= std::min(depth.width - 1, c0 + 1); ++c) {
      const float d = depth.at(r, c);
      if (!IsValidDepth(d)) continue;
      const double dist_sq = (c + 0.5 - u) * (c + 0.5 - u) + (r + 0.5 - v) * (r + 0.5 - v);
      if (found && dist_sq >= nearest_sq) continue;
      found = true;
      nearest_sq = dist_sq;
      *depth_m = d;
    }
  }
  return found;
}

namespace {

// f(t) of the header for view b at world point x (`at`, x projected into b): stored depth minus the point's depth;
// false when b has no surface there.
bool SurfaceOffset(const SacView& b, const ViewPoint& at, double max_spread_m, double* offset_m, double* z_m) {
  if (!at.in_front) return false;
  double stored = 0.0;
  if (!SampleDepth(*b.depth, at.uv.x(), at.uv.y(), max_spread_m, &stored)) return false;
  *offset_m = stored - at.z_m;
  *z_m = at.z_m;
  return true;
}

}  // namespace

void CheckCombineViewCount(size_t num_views) {
  if (num_views > kMaxCombineViews) {
    throw std::invalid_argument("depth combine: " + std::to_string(num_views) + " views to consult, at most " +
                                std::to_string(kMaxCombineViews) + " are supported");
  }
}

SecantPoints SecantPointsOnRay(const SacView& view, double u, double v_px, double depth_m, double step_m) {
  const Eigen::Vector3d ray_cam = view.depth_camera.Unproject(u, v_px, 1.0);
  return {view.world_from_cam * (ray_cam * depth_m), view.world_from_cam * (ray_cam * (depth_m + step_m))};
}

bool IntersectRay(const SacView& b, const ViewPoint& at_depth_in_b, const Eigen::Vector3d& at_next, double depth_m,
                  double step_m, double max_offset_m, double min_slope, RayHit* hit) {
  const double spread_m = 2.0 * max_offset_m;
  double f0 = 0, z0 = 0, f1 = 0, z1 = 0;
  if (!SurfaceOffset(b, at_depth_in_b, spread_m, &f0, &z0)) return false;
  if (std::abs(f0) > spread_m) return false;  // another surface (occluder, occluded, blunder)
  if (!SurfaceOffset(b, ProjectIntoView(b, at_next), spread_m, &f1, &z1)) return false;
  const double slope = (f1 - f0) / step_m;
  if (std::abs(slope) < min_slope) return false;
  const double t = depth_m - f0 / slope;
  if (std::abs(t - depth_m) > max_offset_m) return false;
  hit->depth_m = t;
  hit->slope = slope;
  hit->z_b_m = z0;
  return true;
}

PixelRay PixelRayOf(const SacView& view, double u, double v_px) {
  return {view.world_from_cam.translation, view.world_from_cam.rotation * view.depth_camera.Unproject(u, v_px, 1.0)};
}

bool IntersectPlane(const SacView& b, const ViewPoint& at_depth_in_b, const PixelRay& ray,
                    const Eigen::Vector3d& normal_in_world, double depth_m, double max_offset_m, RayHit* hit) {
  const double spread_m = 2.0 * max_offset_m;
  double f0 = 0, z0 = 0;
  if (!SurfaceOffset(b, at_depth_in_b, spread_m, &f0, &z0)) return false;
  if (std::abs(f0) > spread_m) return false;  // another surface (occluder, occluded, blunder)
  // b's surface point: its ray through the projection, at the stored depth z0 + f0.
  const Eigen::Vector3d ray_b = b.world_from_cam.rotation * b.depth_camera.Unproject(at_depth_in_b.uv.x(),
                                                                                       at_depth_in_b.uv.y(), 1.0);
  const Eigen::Vector3d surface_b = b.world_from_cam.translation + ray_b * (z0 + f0);
  const double n_dot_ray = normal_in_world.dot(ray.direction_in_world);
  const double t = normal_in_world.dot(surface_b - ray.centre_in_world) / n_dot_ray;
  if (std::abs(t - depth_m) > max_offset_m) return false;
  const double n_dot_ray_b = normal_in_world.dot(ray_b);
  hit->depth_m = t;
  hit->slope = n_dot_ray_b != 0.0 ? -n_dot_ray / n_dot_ray_b : -1.0;
  hit->z_b_m = z0;
  return true;
}

double CombineWeight(const std::vector<SacView>& views, uint32_t i, double z_m, double slope,
                     const std::vector<double>& noise_factor, CombineWeights weights) {
  const double factor = noise_factor.empty() ? 1.0 : noise_factor[i];
  switch (weights) {
    case CombineWeights::kEqual:
      return 1.0;
    case CombineWeights::kView:
      return 1.0 / (factor * factor);
    case CombineWeights::kNoise:
      break;
  }
  const double sigma_m = factor * DepthNoiseScale(views[i], z_m) / slope;
  return 1.0 / (sigma_m * sigma_m);
}

double CombineGateM(const std::vector<SacView>& views, uint32_t v, double depth_m,
                    const std::vector<double>& noise_factor, const DepthCombineOptions& options) {
  const double gsd = views[v].GsdAt(depth_m);
  if (noise_factor.empty()) return options.gate_gsd * gsd;
  return std::max(options.gate_gsd * gsd, options.gate_sigmas * DepthSigmaM(views, noise_factor, v, depth_m));
}

CombinedDepth CombineDepth(const std::vector<SacView>& views, uint32_t v, double u, double v_px, double depth_m,
                           const std::vector<uint32_t>& neighbors, const std::vector<double>& noise_factor,
                           const DepthCombineOptions& options, const Eigen::Vector3d& plane_normal_in_world) {
  const SacView& view = views[v];
  const double gsd = view.GsdAt(depth_m);
  auto factor = [&](uint32_t i) { return noise_factor.empty() ? 1.0 : noise_factor[i]; };
  const double own_sigma = factor(v) * DepthNoiseScale(view, depth_m);
  // The secant's second sample: one GSD, or slope_step_sigmas sigma of the own depth where the noise is larger.
  const double step_m = noise_factor.empty() ? gsd : SecantStepM(gsd, own_sigma, options.slope_step_sigmas);
  const double gate_m = CombineGateM(views, v, depth_m, noise_factor, options);
  const SecantPoints ray = SecantPointsOnRay(view, u, v_px, depth_m, step_m);
  // The plane of the pixel's superpixel, where it has one that the ray does not graze.
  const PixelRay pixel_ray = PixelRayOf(view, u, v_px);
  const Eigen::Vector3d ray_unit = pixel_ray.direction_in_world.normalized();
  const bool use_plane = options.surface == CombineSurface::kPlane && plane_normal_in_world.squaredNorm() > 0.0 &&
                         std::abs(plane_normal_in_world.normalized().dot(ray_unit)) >= kPlaneMinCos;
  // ... for the views that see the point within kPlaneMaxPairAngleDeg of the ray.
  const double min_pair_cos = std::cos(kPlaneMaxPairAngleDeg * M_PI / 180.0);

  auto weight = [&](uint32_t i, double z_m, double slope) {
    return CombineWeight(views, i, z_m, slope, noise_factor, options.weights);
  };
  CheckCombineViewCount(neighbors.size());
  // One pass: every neighbour's surface on the ray, found from the ray's point at depth `centre_m` (the own depth,
  // then the previous pass's mean), within `centre_gate_m` of that point and the gate of the own depth; their
  // weighted mean with the own depth.
  auto pass = [&](double centre_m, double centre_gate_m) {
    const SecantPoints at = centre_m == depth_m ? ray : SecantPointsOnRay(view, u, v_px, centre_m, step_m);
    double weight_sum = weight(v, depth_m, 1.0);
    double weighted_depth = weight_sum * depth_m;
    double others_weight = 0.0;
    double others_weighted_depth = 0.0;
    CombinedDepth result;
    ViewPoint at_centre[kMaxCombineViews];
    ProjectForSecants(views, neighbors, at.at_depth, at_centre);
    for (size_t i = 0; i < neighbors.size(); ++i) {
      const uint32_t nb = neighbors[i];
      RayHit hit;
      const bool along_plane =
          use_plane && (at.at_depth - views[nb].world_from_cam.translation).normalized().dot(ray_unit) >= min_pair_cos;
      const bool found =
          along_plane
              ? IntersectPlane(views[nb], at_centre[i], pixel_ray, plane_normal_in_world, centre_m, centre_gate_m,
                               &hit)
              : IntersectRay(views[nb], at_centre[i], at.at_next, centre_m, step_m, centre_gate_m, options.min_slope,
                             &hit);
      if (!found || std::abs(hit.depth_m - depth_m) > gate_m) continue;
      const double w = weight(nb, hit.z_b_m, std::abs(hit.slope));
      weight_sum += w;
      weighted_depth += w * hit.depth_m;
      others_weight += w;
      others_weighted_depth += w * hit.depth_m;
      ++result.support;
    }
    result.depth_m = weighted_depth / weight_sum;
    if (others_weight > 0.0) {
      result.others_weight = others_weight;
      result.others_depth_m = others_weighted_depth / others_weight;
    }
    return result;
  };
  CombinedDepth out = pass(depth_m, gate_m);
  double centre_m = depth_m;
  for (int p = 1; p < options.passes && out.support > 1; ++p) {
    // Converged: the centre moved less than later_pass_min_shift_gsd local GSDs (see the header).
    if (std::abs(out.depth_m - centre_m) < options.later_pass_min_shift_gsd * gsd) break;
    centre_m = out.depth_m;
    out = pass(centre_m, options.later_pass_gate * gate_m);
  }
  return out;
}

}  // namespace sacfuse
