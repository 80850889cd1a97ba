#pragma once
// Depth pixels to world points.
#include "core/camera.h"
#include "core/point.h"
#include "core/raster.h"
#include "core/rigid3.h"
#include "core/view.h"

namespace sacfuse {

// The one pixel convention of sacfuse: depth pixel (col, row) stands for the ray through its centre
// (col + 0.5, row + 0.5) (COLMAP's stereo_fusion uses the corner, a half-pixel shift we do not copy; measured
// worse on aerial-bench, see docs/design.md). Camera-frame point at z-depth `depth_m` (depth 1: the ray's direction with
// z = 1); `depth_camera` is the view's camera scaled to the depth raster.
inline Eigen::Vector3d DepthPixelInCamera(const PinholeCamera& depth_camera, int col, int row, double depth_m) {
  return depth_camera.Unproject(col + 0.5, row + 0.5, depth_m);
}

// World point of depth pixel (col, row) with z-depth `depth_m`.
inline Eigen::Vector3d DepthPixelToWorld(const PinholeCamera& depth_camera, const Rigid3d& world_from_cam, int col,
                                         int row, double depth_m) {
  return world_from_cam * DepthPixelInCamera(depth_camera, col, row, depth_m);
}

// Streams every valid depth pixel of one view into `sink` as a FusedPoint (colour sampled from `image` at the
// pixel centre when given, which may have another resolution than the depth map). Returns the number of points.
size_t BackprojectDepthMap(const View& view, const DepthMap& depth, const RgbImage* image, PointSink& sink);

}  // namespace sacfuse
