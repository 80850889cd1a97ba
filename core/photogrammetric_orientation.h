#pragma once
// Classical photogrammetric exterior orientation (projection centre + omega, phi, kappa) and its conversion to
// sacfuse's cam_from_world. Pure math, no I/O.
//
// Frames
// - Photogrammetric camera (image space) frame, as in the standard textbooks (Kraus, Luhmann): origin at the
//   projection centre, x to the right of the image, y to the TOP of the image, z toward the viewer (out of the
//   back of the camera); the camera looks along -z. A point in front of the camera has z < 0.
// - sacfuse camera frame (core/camera.h, COLMAP's): x right, y DOWN, z forward (viewing direction).
//   point_in_sacfuse_cam = diag(1, -1, -1) * point_in_photo_cam.
// - Object frame: the project CRS (x east, y north, z up for UTM and local ENU), or the local east-north-up frame
//   at the camera when an attitude is given w.r.t. local ENU (the caller rotates it into the project frame).
//
// Rotation
//   R = R_x(omega) * R_y(phi) * R_z(kappa), angles in degrees, each a right-handed (counter-clockwise seen from
//   the positive axis) rotation:
//     R_x(w) = [1 0 0; 0 cos w -sin w; 0 sin w cos w], R_y(p) = [cos p 0 sin p; 0 1 0; -sin p 0 cos p],
//     R_z(k) = [cos k -sin k 0; sin k cos k 0; 0 0 1].
//   R maps vectors of the photogrammetric camera frame INTO the object frame (image to object):
//     point_in_object = R * point_in_photo_cam + projection_centre,
//   so its columns are the camera's x, y, z axes in object coordinates, and
//     R = [cos p cos k, -cos p sin k, sin p;
//          cos w sin k + sin w sin p cos k, cos w cos k - sin w sin p sin k, -sin w cos p;
//          sin w sin k - cos w sin p cos k, sin w cos k + cos w sin p sin k, cos w cos p].
//   omega = phi = kappa = 0 is a nadir camera: looking straight down, image x (right) along object +x (east),
//   image top along object +y (north). kappa = 90 turns image x to north (image top to west); omega = 90 looks
//   horizontally north with the image top up; phi = 90 looks horizontally west with the image top north.
#include <Eigen/Core>

#include "core/rigid3.h"

namespace sacfuse {

struct OmegaPhiKappa {
  double omega_deg = 0.0;  // about the object x axis, applied last (outermost)
  double phi_deg = 0.0;    // about y; in [-90, 90] when decomposed from a matrix
  double kappa_deg = 0.0;  // about z, applied first (innermost)
};

// R = R_x(omega) R_y(phi) R_z(kappa): photogrammetric camera frame -> object frame.
Eigen::Matrix3d ObjectFromPhotoCameraRotation(const OmegaPhiKappa& angles);

// The angles of a rotation matrix (the inverse of the above): phi in [-90, 90], omega and kappa in (-180, 180].
// At phi = +-90 (gimbal lock, only omega + kappa or omega - kappa is defined) kappa = 0 is returned.
OmegaPhiKappa OmegaPhiKappaFromRotation(const Eigen::Matrix3d& object_from_photo_camera);

// sacfuse's pose from the photogrammetric rotation (camera -> object) and projection centre (object frame):
// cam_from_world.rotation = diag(1, -1, -1) * R^T, translation = -rotation * centre.
Rigid3d CamFromWorldFromPhotogrammetric(const Eigen::Matrix3d& object_from_photo_camera,
                                        const Eigen::Vector3d& centre_in_world);
// The inverse: R (photogrammetric camera -> world) of a sacfuse pose. The centre is
// cam_from_world.Inverse().translation.
Eigen::Matrix3d PhotoCameraToWorldRotation(const Rigid3d& cam_from_world);

// Whether `m` is a proper rotation: |m^T m - I| <= tolerance element-wise and det(m) > 0.
bool IsRotationMatrix(const Eigen::Matrix3d& m, double tolerance = 1e-6);

}  // namespace sacfuse
