#pragma once
// Rigid transform b_from_a: point_in_b = rotation * point_in_a + translation. Double precision throughout:
// world frames are projected CRS coordinates with northings around 6e6 m.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sacfuse {

struct Rigid3d {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator*(const Eigen::Vector3d& point) const { return rotation * point + translation; }
  Rigid3d operator*(const Rigid3d& other) const {  // (c_from_b * b_from_a) = c_from_a
    return Rigid3d{rotation * other.rotation, rotation * other.translation + translation};
  }
  Rigid3d Inverse() const {
    const Eigen::Quaterniond inv = rotation.conjugate();
    return Rigid3d{inv, -(inv * translation)};
  }
};

}  // namespace sacfuse
