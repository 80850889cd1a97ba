#pragma once
// The one least-squares plane fit of sacfuse (normals of depth maps, in core and in the simulator's MVS-like normal
// maps): points are added relative to a nearby origin (for conditioning), the normal is the eigenvector of the
// smallest eigenvalue of their covariance.
#include <Eigen/Core>

namespace sacfuse {

class PlaneFit {
 public:
  void Add(const Eigen::Vector3d& q) {
    sum_ += q;
    sum_outer_ += q * q.transpose();
    ++count_;
  }
  int count() const { return count_; }
  // Unit normal (sign arbitrary) and, when asked, the eigenvalues of the covariance (mean squared distances, m^2)
  // in ascending order. Needs count() >= 1.
  Eigen::Vector3d Normal(Eigen::Vector3d* eigenvalues = nullptr) const;

 private:
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer_ = Eigen::Matrix3d::Zero();
  int count_ = 0;
};

}  // namespace sacfuse
