#include "tools/sim/stereo_rectify.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

namespace sacfuse::sim {
namespace {

constexpr int kDisparityMargin = 4;  // pixels of search beyond each end of the depth range

}  // namespace

Eigen::Matrix3d IndexCameraMatrix(const PinholeCamera& camera) {
  Eigen::Matrix3d k;
  k << camera.fx, 0.0, camera.cx - 0.5, 0.0, camera.fy, camera.cy - 0.5, 0.0, 0.0, 1.0;
  return k;
}

Eigen::Matrix3d RectifyingRotation(const Rigid3d& ref_cam_from_world, const Rigid3d& src_cam_from_world) {
  const Eigen::Matrix3d ref_from_world = ref_cam_from_world.rotation.toRotationMatrix();
  const Eigen::Matrix3d src_from_ref = src_cam_from_world.rotation.toRotationMatrix() * ref_from_world.transpose();
  const Eigen::Vector3d baseline_in_ref =
      ref_from_world * (src_cam_from_world.Inverse().translation - ref_cam_from_world.Inverse().translation);
  if (!(baseline_in_ref.norm() > 1e-9)) throw std::invalid_argument("RectifyPair: the two camera centres coincide");
  // x along the baseline; z between the two optical axes, made orthogonal to x; y = z cross x (right-handed).
  const Eigen::Vector3d e1 = baseline_in_ref.normalized();
  Eigen::Vector3d e3 = Eigen::Vector3d::UnitZ() + src_from_ref.transpose() * Eigen::Vector3d::UnitZ();
  e3 -= e3.dot(e1) * e1;
  if (!(e3.norm() > 1e-9)) throw std::invalid_argument("RectifyPair: the baseline runs along the optical axes");
  e3.normalize();
  Eigen::Matrix3d rect_from_ref;
  rect_from_ref.row(0) = e1.transpose();
  rect_from_ref.row(1) = e3.cross(e1).transpose();
  rect_from_ref.row(2) = e3.transpose();
  return rect_from_ref;
}

RectifiedPair RectifyPair(const PinholeCamera& ref_camera, const Rigid3d& ref_cam_from_world,
                          const PinholeCamera& src_camera, const Rigid3d& src_cam_from_world, double z_near_m,
                          double z_far_m, int max_disparities) {
  if (!(z_near_m > 0.0) || !(z_far_m > z_near_m)) throw std::invalid_argument("RectifyPair: empty depth range");
  RectifiedPair pair;
  pair.rect_from_ref = RectifyingRotation(ref_cam_from_world, src_cam_from_world);
  const Eigen::Matrix3d ref_from_world = ref_cam_from_world.rotation.toRotationMatrix();
  const Eigen::Matrix3d src_from_ref = src_cam_from_world.rotation.toRotationMatrix() * ref_from_world.transpose();
  pair.baseline_m = (src_cam_from_world.Inverse().translation - ref_cam_from_world.Inverse().translation).norm();
  pair.focal_px = ref_camera.fx;

  // The reference image's corners on the rectified canvas.
  const Eigen::Matrix3d ref_k = IndexCameraMatrix(ref_camera);
  const Eigen::Matrix3d ref_k_inv = ref_k.inverse();
  double x_min = std::numeric_limits<double>::infinity(), y_min = x_min;
  double x_max = -x_min, y_max = -x_min;
  for (const double c : {0.0, ref_camera.width - 1.0}) {
    for (const double r : {0.0, ref_camera.height - 1.0}) {
      const Eigen::Vector3d q = pair.rect_from_ref * (ref_k_inv * Eigen::Vector3d(c, r, 1.0));
      if (!(q.z() > 1e-9)) throw std::invalid_argument("RectifyPair: the reference image is not in front of the canvas");
      x_min = std::min(x_min, pair.focal_px * q.x() / q.z());
      x_max = std::max(x_max, pair.focal_px * q.x() / q.z());
      y_min = std::min(y_min, pair.focal_px * q.y() / q.z());
      y_max = std::max(y_max, pair.focal_px * q.y() / q.z());
    }
  }
  x_min = std::floor(x_min), y_min = std::floor(y_min), x_max = std::ceil(x_max), y_max = std::ceil(y_max);

  // Disparity range; the search width cap gives up the nearest depths first.
  const double fb = pair.focal_px * pair.baseline_m;
  const double max_search = std::max(16, max_disparities);
  z_near_m = std::max(z_near_m, fb / (fb / z_far_m + max_search - 2.0 * kDisparityMargin));
  const double d_min = fb / z_far_m, d_max = fb / z_near_m;
  pair.disparity_shift = static_cast<int>(std::floor(d_min)) - kDisparityMargin;
  const int search = static_cast<int>(std::ceil((d_max - d_min + 2.0 * kDisparityMargin) / 16.0)) * 16;
  pair.num_disparities = std::min(search, static_cast<int>(max_search) / 16 * 16);
  pair.z_near_m = z_near_m;
  pair.z_far_m = z_far_m;

  const int pad = pair.num_disparities + 2;
  pair.left_cx = -x_min + pad;
  pair.right_cx = pair.left_cx + pair.disparity_shift;
  pair.cy = -y_min;
  pair.width = static_cast<int>(x_max - x_min) + pad + 1;
  pair.height = static_cast<int>(y_max - y_min) + 1;

  Eigen::Matrix3d left_k, right_k;
  left_k << pair.focal_px, 0.0, pair.left_cx, 0.0, pair.focal_px, pair.cy, 0.0, 0.0, 1.0;
  right_k << pair.focal_px, 0.0, pair.right_cx, 0.0, pair.focal_px, pair.cy, 0.0, 0.0, 1.0;
  const Eigen::Matrix3d ref_from_rect = pair.rect_from_ref.transpose();
  pair.left_to_ref = ref_k * ref_from_rect * left_k.inverse();
  pair.right_to_src = IndexCameraMatrix(src_camera) * src_from_ref * ref_from_rect * right_k.inverse();
  return pair;
}

}  // namespace sacfuse::sim
