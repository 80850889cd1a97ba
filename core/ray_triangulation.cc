#include "core/ray_triangulation.h"

#include <cmath>

#include <Eigen/Dense>

namespace sacfuse {

std::optional<Eigen::Vector3d> TriangulateRays(const std::vector<TriangulationRay>& rays) {
  if (rays.empty()) return std::nullopt;
  // Solve around the first measured point so UTM-sized coordinates cost no precision.
  const Eigen::Vector3d origin = rays.front().measured;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const TriangulationRay& ray : rays) {
    const Eigen::Vector3d r = ray.direction.normalized();
    const Eigen::Matrix3d along = r * r.transpose();
    Eigen::Matrix3d w = (Eigen::Matrix3d::Identity() - along) / (ray.lateral_sigma_m * ray.lateral_sigma_m);
    if (ray.along_sigma_m > 0) w += along / (ray.along_sigma_m * ray.along_sigma_m);
    a += w;
    b += w * (ray.measured - origin);
  }
  // Singular when every ray is parallel and no along term pins the position: check the conditioning.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(a);
  const Eigen::Vector3d ev = solver.eigenvalues();
  if (!(ev(0) > 1e-9 * ev(2))) return std::nullopt;
  return origin + a.ldlt().solve(b);
}

}  // namespace sacfuse
