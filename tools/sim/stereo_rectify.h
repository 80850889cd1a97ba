#pragma once
// Rectification of one stereo pair (a reference view and a source view) for a matcher that searches along image
// rows (OpenCV's StereoSGBM): both views are resampled onto canvases of one common rotation whose x axis is the
// baseline (reference -> source) and whose z axis lies between the two optical axes, with one focal length (the
// reference's), so that a surface point lands on the same canvas row in both and its disparity u_left - u_right
// plus the canvas shift is f B / Z. Written out (what cv::stereoRectify does) so that pairs whose baseline runs
// along the image columns (along-track pairs of a camera flown sideways) need no special case.
//
// Pixel coordinates: canvases use OpenCV's index convention (pixel (c, r) at (c, r)); the views' cameras are
// sacfuse's (pixel (c, r) centred at (c + 0.5, r + 0.5), core/camera.h), converted here once.
//
// The disparity search covers the depths [z_near_m, z_far_m] (in the rectified frame) and is clipped to
// max_disparities (the nearest depths are given up first); the left canvas is padded by the search width on the
// left so that the matcher's invalid band of numDisparities columns falls outside the reference image.
#include <Eigen/Core>

#include "core/camera.h"
#include "core/rigid3.h"

namespace sacfuse::sim {

struct RectifiedPair {
  Eigen::Matrix3d rect_from_ref = Eigen::Matrix3d::Identity();  // reference camera frame -> rectified frame
  double baseline_m = 0.0;
  double focal_px = 0.0;          // of both canvases
  int width = 0, height = 0;      // canvas size, pixels (both canvases)
  double left_cx = 0.0, right_cx = 0.0, cy = 0.0;  // canvas principal points (index convention)
  int disparity_shift = 0;        // f B / Z = canvas disparity + disparity_shift
  int num_disparities = 0;        // the matcher's search width (a multiple of 16)
  double z_near_m = 0.0, z_far_m = 0.0;  // the depth range searched (after clipping)
  // Homographies canvas pixel -> image pixel (index convention), for cv::warpPerspective with WARP_INVERSE_MAP.
  Eigen::Matrix3d left_to_ref = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d right_to_src = Eigen::Matrix3d::Identity();

  // Depth along the rectified z axis of a canvas disparity, metres.
  double RectifiedDepth(double canvas_disparity) const {
    return focal_px * baseline_m / (canvas_disparity + disparity_shift);
  }
};

// The rotation reference camera frame -> rectified frame of the pair (RectifiedPair::rect_from_ref), for choosing
// the depth range before rectifying. Throws std::invalid_argument when the two centres coincide or the baseline
// runs along both optical axes.
Eigen::Matrix3d RectifyingRotation(const Rigid3d& ref_cam_from_world, const Rigid3d& src_cam_from_world);

// Throws std::invalid_argument as RectifyingRotation, or when the depth range is empty.
RectifiedPair RectifyPair(const PinholeCamera& ref_camera, const Rigid3d& ref_cam_from_world,
                          const PinholeCamera& src_camera, const Rigid3d& src_cam_from_world, double z_near_m,
                          double z_far_m, int max_disparities);

// The camera matrix of `camera` in the index convention (principal point shifted by half a pixel).
Eigen::Matrix3d IndexCameraMatrix(const PinholeCamera& camera);

}  // namespace sacfuse::sim
