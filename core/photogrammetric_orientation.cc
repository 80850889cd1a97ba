#include "core/photogrammetric_orientation.h"

#include <Eigen/Geometry>
#include <cmath>

namespace sacfuse {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kRadToDeg = 180.0 / kPi;

// sacfuse camera (x right, y down, z forward) from photogrammetric camera (x right, y up, z back).
const Eigen::Matrix3d& SacfuseFromPhotoCamera() {
  static const Eigen::Matrix3d flip = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  return flip;
}

}  // namespace

Eigen::Matrix3d ObjectFromPhotoCameraRotation(const OmegaPhiKappa& a) {
  const double w = a.omega_deg * kDegToRad, p = a.phi_deg * kDegToRad, k = a.kappa_deg * kDegToRad;
  const double cw = std::cos(w), sw = std::sin(w), cp = std::cos(p), sp = std::sin(p), ck = std::cos(k),
               sk = std::sin(k);
  Eigen::Matrix3d rx, ry, rz;
  rx << 1, 0, 0, 0, cw, -sw, 0, sw, cw;
  ry << cp, 0, sp, 0, 1, 0, -sp, 0, cp;
  rz << ck, -sk, 0, sk, ck, 0, 0, 0, 1;
  return rx * ry * rz;
}

OmegaPhiKappa OmegaPhiKappaFromRotation(const Eigen::Matrix3d& r) {
  // r(0,2) = sin phi, r(0,0) = cos phi cos kappa, r(0,1) = -cos phi sin kappa, r(1,2) = -sin omega cos phi,
  // r(2,2) = cos omega cos phi. atan2 of (sin, cos-norm) keeps phi accurate near +-90 where asin is ill-conditioned.
  OmegaPhiKappa a;
  const double cos_phi = std::hypot(r(0, 0), r(0, 1));
  a.phi_deg = std::atan2(r(0, 2), cos_phi) * kRadToDeg;
  if (cos_phi > 1e-12) {
    a.omega_deg = std::atan2(-r(1, 2), r(2, 2)) * kRadToDeg;
    a.kappa_deg = std::atan2(-r(0, 1), r(0, 0)) * kRadToDeg;
  } else {
    // Gimbal lock: with kappa = 0, R = R_x(omega) R_y(phi) has r(1,1) = cos omega, r(2,1) = sin omega.
    a.kappa_deg = 0.0;
    a.omega_deg = std::atan2(r(2, 1), r(1, 1)) * kRadToDeg;
  }
  return a;
}

Rigid3d CamFromWorldFromPhotogrammetric(const Eigen::Matrix3d& object_from_photo_camera,
                                        const Eigen::Vector3d& centre_in_world) {
  const Eigen::Matrix3d cam_from_world = SacfuseFromPhotoCamera() * object_from_photo_camera.transpose();
  Rigid3d pose;
  pose.rotation = Eigen::Quaterniond(cam_from_world).normalized();
  pose.translation = -(pose.rotation * centre_in_world);
  return pose;
}

Eigen::Matrix3d PhotoCameraToWorldRotation(const Rigid3d& cam_from_world) {
  // cam_from_world = F R^T  =>  R = (F^T cam_from_world)^T = cam_from_world^T F (F is its own inverse).
  return cam_from_world.rotation.normalized().toRotationMatrix().transpose() * SacfuseFromPhotoCamera();
}

bool IsRotationMatrix(const Eigen::Matrix3d& m, double tolerance) {
  if (!m.allFinite()) return false;
  const Eigen::Matrix3d e = m.transpose() * m - Eigen::Matrix3d::Identity();
  return e.cwiseAbs().maxCoeff() <= tolerance && m.determinant() > 0.0;
}

}  // namespace sacfuse
