#include "core/plane_fit.h"

#include <Eigen/Eigenvalues>

namespace sacfuse {

Eigen::Vector3d PlaneFit::Normal(Eigen::Vector3d* eigenvalues) const {
  const Eigen::Vector3d mean = sum_ / count_;
  const Eigen::Matrix3d cov = sum_outer_ / count_ - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(cov);
  if (eigenvalues != nullptr) *eigenvalues = solver.eigenvalues();
  return solver.eigenvectors().col(0);
}

}  // namespace sacfuse
