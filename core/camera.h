#pragma once
// Undistorted pinhole intrinsics in pixels.
//
// Pixel convention (COLMAP's): image coordinates (u, v) put (0, 0) at the top-left CORNER of the top-left
// pixel, u to the right, v down; the centre of pixel (col, row) is (col + 0.5, row + 0.5). Camera frame:
// x right, y down, z forward (viewing direction); depth is the z coordinate in the camera frame, not range.
#include <Eigen/Core>

namespace sacfuse {

struct PinholeCamera {
  int width = 0;    // pixels
  int height = 0;   // pixels
  double fx = 0.0;  // focal length, pixels
  double fy = 0.0;
  double cx = 0.0;  // principal point, pixels (corner convention above)
  double cy = 0.0;

  // Image coordinates of a point in the camera frame (z > 0 assumed).
  Eigen::Vector2d Project(const Eigen::Vector3d& point_in_cam) const {
    return {fx * point_in_cam.x() / point_in_cam.z() + cx, fy * point_in_cam.y() / point_in_cam.z() + cy};
  }
  // Point in the camera frame at image coordinates (u, v) and z-depth.
  Eigen::Vector3d Unproject(double u, double v, double depth_z) const {
    return {(u - cx) / fx * depth_z, (v - cy) / fy * depth_z, depth_z};
  }
  // The same camera resampled to another raster size (e.g. a half-resolution depth map).
  PinholeCamera Scaled(int new_width, int new_height) const {
    const double sx = static_cast<double>(new_width) / width;
    const double sy = static_cast<double>(new_height) / height;
    return {new_width, new_height, fx * sx, fy * sy, cx * sx, cy * sy};
  }
  bool IsValid() const { return width > 0 && height > 0 && fx > 0 && fy > 0; }

  // Square pixels, principal point at the image centre.
  static PinholeCamera Centered(int width_px, int height_px, double focal_px) {
    return {width_px, height_px, focal_px, focal_px, 0.5 * width_px, 0.5 * height_px};
  }
};

}  // namespace sacfuse
