#include "core/depth_normals.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

namespace sacfuse {
namespace {

constexpr double kStepGsdPerPixel = 3.0;
constexpr int kMinPlanePixels = 5;

}  // namespace

NormalMap PlaneFitNormalsInWorld(const SacView& view, int radius_px) {
  const DepthMap& depth = *view.depth;
  NormalMap normals(depth.width, depth.height, 3, 0.0f);
  const PinholeCamera& cam = view.depth_camera;
  const Eigen::Matrix3d world_from_cam_rot = view.world_from_cam.rotation.toRotationMatrix();
  tbb::parallel_for(0, depth.height, [&](int row) {
    for (int col = 0; col < depth.width; ++col) {
      const float dc = depth.at(row, col);
      if (!IsValidDepth(dc)) continue;
      const Eigen::Vector3d centre = cam.Unproject(col + 0.5, row + 0.5, dc);
      const double gsd = view.GsdAt(dc);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();
      int count = 0;
      for (int r = std::max(0, row - radius_px); r <= std::min(depth.height - 1, row + radius_px); ++r) {
        for (int c = std::max(0, col - radius_px); c <= std::min(depth.width - 1, col + radius_px); ++c) {
          const float d = depth.at(r, c);
          if (!IsValidDepth(d)) continue;
          const int steps = std::max(std::abs(r - row), std::abs(c - col)) + 1;
          if (std::abs(d - dc) > kStepGsdPerPixel * gsd * steps) continue;
          const Eigen::Vector3d q = cam.Unproject(c + 0.5, r + 0.5, d) - centre;
          sum += q;
          sum_outer += q * q.transpose();
          ++count;
        }
      }
      if (count < kMinPlanePixels) continue;
      const Eigen::Vector3d mean = sum / count;
      const Eigen::Matrix3d cov = sum_outer / count - mean * mean.transpose();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
      solver.computeDirect(cov);
      Eigen::Vector3d n = solver.eigenvectors().col(0);
      if (n.dot(centre) > 0) n = -n;  // face the camera
      const Eigen::Vector3d w = (world_from_cam_rot * n).normalized();
      for (int k = 0; k < 3; ++k) normals.at(row, col, k) = static_cast<float>(w[k]);
    }
  });
  return normals;
}

}  // namespace sacfuse
