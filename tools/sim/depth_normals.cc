#include "tools/sim/depth_normals.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace sacfuse::sim {

NormalMap NormalsFromDepth(const DepthMap& depth, const PinholeCamera& cam) {
  const int w = depth.width, h = depth.height;
  NormalMap normals(w, h, 3, 0.0f);
  const double focal = std::min(cam.fx, cam.fy);
#pragma omp parallel for schedule(dynamic, 16)
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) {
      const float d0 = depth.at(row, col);
      if (!IsValidDepth(d0)) continue;
      const Eigen::Vector3d p0 = cam.Unproject(col + 0.5, row + 0.5, d0);
      const double max_step = std::max(0.3, 4.0 * d0 / focal);
      Eigen::Vector3d pts[9];
      int n = 0;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int r = row + dr, c = col + dc;
          if (!depth.Contains(r, c)) continue;
          const float d = depth.at(r, c);
          if (!IsValidDepth(d) || std::abs(d - d0) > max_step) continue;
          pts[n] = cam.Unproject(c + 0.5, r + 0.5, d) - p0;  // relative to the centre for conditioning
          mean += pts[n];
          ++n;
        }
      }
      Eigen::Vector3d normal = -p0.normalized();
      if (n >= 3) {
        mean /= n;
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (int k = 0; k < n; ++k) cov += (pts[k] - mean) * (pts[k] - mean).transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
        solver.computeDirect(cov);
        const Eigen::Vector3d ev = solver.eigenvalues();
        // Eigenvalues ascending; a line-like neighbourhood (two tiny eigenvalues) has no plane.
        if (ev[1] > 1e-12 && ev[0] < 0.5 * ev[1]) normal = solver.eigenvectors().col(0).normalized();
      }
      if (normal.dot(p0) > 0.0) normal = -normal;
      // Edge-on planes (walls seen at grazing angles) are tilted to >= ~3 degrees toward the camera, so every
      // normal strictly faces it as MVS normals do.
      const Eigen::Vector3d to_camera = -p0.normalized();
      const double facing = normal.dot(to_camera);
      if (facing < 0.05) normal = (normal + (0.05 - facing) * to_camera).normalized();
      for (int k = 0; k < 3; ++k) normals.at(row, col, k) = static_cast<float>(normal[k]);
    }
  }
  return normals;
}

}  // namespace sacfuse::sim
