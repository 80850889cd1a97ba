#include "core/combine_anchors.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {

CombineAnchors::CombineAnchors(const PixelWindow& patch) : patch_(patch), anchors_(patch.num_pixels()) {}

void CombineAnchors::Set(int row, int col, const CombinedDepth& combined) {
  Anchor& a = anchors_[static_cast<size_t>(row - patch_.row_begin) * patch_.width() + (col - patch_.col_begin)];
  a.valid = combined.others_weight > 0.0;
  a.others_depth_m = combined.others_depth_m;
  a.others_weight = combined.others_weight;
}

const CombineAnchors::Anchor* CombineAnchors::At(int row, int col) const {
  if (row < patch_.row_begin || row >= patch_.row_end || col < patch_.col_begin || col >= patch_.col_end) {
    return nullptr;
  }
  const Anchor& a = anchors_[static_cast<size_t>(row - patch_.row_begin) * patch_.width() + (col - patch_.col_begin)];
  return a.valid ? &a : nullptr;
}

bool CombineAnchors::Interpolate(const std::vector<SacView>& views, uint32_t v, int row, int col, double depth_m,
                                 const std::vector<double>& noise_factor, const DepthCombineOptions& options,
                                 const Eigen::Vector3d& plane_normal_in_world, double* combined_depth_m) const {
  const SacView& view = views[v];
  // An anchor's surface point (at depth M on its ray) carried along the plane onto the pixel's ray: both rays
  // leave the same centre, so t = M (n . r_anchor) / (n . r_pixel), r the rays' directions (unit z) in the camera
  // frame. Without a plane, or where the pixel's ray grazes it (kPlaneMinCos, as in the combine), t = M.
  const PinholeCamera& cam = view.depth_camera;
  auto ray = [&](int r, int c) { return cam.Unproject(c + 0.5, r + 0.5, 1.0); };
  Eigen::Vector3d normal_in_cam = Eigen::Vector3d::Zero();
  double n_dot_pixel_ray = 0.0;
  if (plane_normal_in_world.squaredNorm() > 0.0) {
    normal_in_cam = view.cam_from_world_rotation * plane_normal_in_world.normalized();
    const Eigen::Vector3d pixel_ray = ray(row, col);
    n_dot_pixel_ray = normal_in_cam.dot(pixel_ray);
    if (std::abs(n_dot_pixel_ray) < kPlaneMinCos * pixel_ray.norm()) n_dot_pixel_ray = 0.0;
  }

  double lo = 0.0, hi = 0.0, depth_sum = 0.0, weight_sum = 0.0;
  int count = 0;
  for (int r = row - 1; r <= row + 1; ++r) {
    for (int c = col - 1; c <= col + 1; ++c) {
      const Anchor* a = (r == row && c == col) ? nullptr : At(r, c);
      if (a == nullptr) continue;
      const double t = n_dot_pixel_ray != 0.0 ? a->others_depth_m * normal_in_cam.dot(ray(r, c)) / n_dot_pixel_ray
                                              : a->others_depth_m;
      lo = count == 0 ? t : std::min(lo, t);
      hi = count == 0 ? t : std::max(hi, t);
      depth_sum += t;
      weight_sum += a->others_weight;
      ++count;
    }
  }
  if (count < kMinAnchorNeighbours) return false;
  const double own_sigma_m = noise_factor.empty() ? 0.0 : DepthSigmaM(views, noise_factor, v, depth_m);
  const double tolerance_m = std::max(kAnchorToleranceGsd * view.GsdAt(depth_m), kAnchorToleranceSigmas * own_sigma_m);
  if (hi - lo > tolerance_m) return false;
  const double others_depth_m = depth_sum / count;
  if (std::abs(others_depth_m - depth_m) > CombineGateM(views, v, depth_m, noise_factor, options)) return false;
  const double others_weight = weight_sum / count;
  const double own_weight = CombineWeight(views, v, depth_m, 1.0, noise_factor, options.weights);
  *combined_depth_m = (own_weight * depth_m + others_weight * others_depth_m) / (own_weight + others_weight);
  return true;
}

}  // namespace sacfuse
