#pragma once
// What SAC needs of one view, at depth-map resolution. The rasters are owned by the caller (jobs/), which decides
// what is in memory; core never reads files.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/camera.h"
#include "core/consistency_graph.h"
#include "core/raster.h"
#include "core/rigid3.h"
#include "core/superpixels.h"
#include "core/view.h"

namespace sacfuse {

struct SacView {
  View view;                                   // intrinsics at image resolution, pose
  PinholeCamera depth_camera;                  // view.camera scaled to the depth raster
  Rigid3d world_from_cam;                      // inverse pose, cached
  // view.cam_from_world as a matrix, cached: LookupDepth, the hottest call of SAC, rotates with 9 multiply-adds
  // instead of the quaternion's ~30 operations.
  Eigen::Matrix3d cam_from_world_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d cam_from_world_translation = Eigen::Vector3d::Zero();
  const DepthMap* depth = nullptr;             // z-depth, metres
  const SuperpixelMap* superpixels = nullptr;  // same size as depth
  const RgbImage* image = nullptr;             // colours (any resolution); null = grey points
  const ConsistencyGraph* consistency = nullptr;  // dense-matching consistency; null when the input has none

  // A world point in this view's camera frame, through the cached matrix.
  Eigen::Vector3d PointInCamera(const Eigen::Vector3d& point_in_world) const {
    return cam_from_world_rotation * point_in_world + cam_from_world_translation;
  }

  // Local ground sampling distance at depth z: metres covered by one depth pixel.
  double GsdAt(double depth_m) const { return depth_m / depth_camera.fx; }
};

// Builds the cached fields (depth_camera, world_from_cam) from view and rasters.
SacView MakeSacView(const View& view, const DepthMap* depth, const SuperpixelMap* superpixels, const RgbImage* image,
                    const ConsistencyGraph* consistency = nullptr);

// Where a world point falls in a view's depth raster.
struct DepthLookup {
  bool inside = false;      // in front of the camera and inside the raster
  int row = 0, col = 0;     // pixel
  double z_m = 0.0;         // the point's depth in this view
  float stored_depth_m = 0.0f;  // the depth map's value at the pixel (<= 0 invalid)
};
// The lookups are inline: they are SAC's innermost calls (tens per pixel from the point tests, the better-view
// search and the coverage chain, all in other files). As calls into sac_view.cc they cost ~5 % of a run (issue 13;
// aerial-bench Montpellier, 13 alternating pairs of runs: median ratio 0.95, 11 of 13 faster, the same cloud).
// Where a point already in the view's camera frame falls, without reading the depth map (stored_depth_m stays 0):
// for callers that test the point's depth, or a bound on the stored depth, before paying for the read.
inline DepthLookup ProjectIntoDepth(const SacView& view, const Eigen::Vector3d& point_in_camera) {
  DepthLookup out;
  if (point_in_camera.z() <= 0) return out;
  const Eigen::Vector2d uv = view.depth_camera.Project(point_in_camera);
  if (!(uv.x() >= 0 && uv.y() >= 0 && uv.x() < view.depth->width && uv.y() < view.depth->height)) return out;
  out.inside = true;
  out.col = static_cast<int>(uv.x());
  out.row = static_cast<int>(uv.y());
  out.z_m = point_in_camera.z();
  return out;
}
// The same for a point already in the view's camera frame (view.PointInCamera), for callers that test its depth
// before paying for the read of the depth map.
inline DepthLookup LookupDepthInCamera(const SacView& view, const Eigen::Vector3d& point_in_camera) {
  DepthLookup out = ProjectIntoDepth(view, point_in_camera);
  if (out.inside) out.stored_depth_m = view.depth->at(out.row, out.col);
  return out;
}
// The same for a world point.
inline DepthLookup LookupDepth(const SacView& view, const Eigen::Vector3d& point_in_world) {
  return LookupDepthInCamera(view, view.PointInCamera(point_in_world));
}

// Prefetches: start loading what a read of the depth map will need and return at once, so that the cache misses of
// a point's reads in several views overlap instead of following one another (issue 13; 40 views are read per point,
// and most of SAC's time was waiting for these misses). They change no result.
// Depth pixel (row, col), inside the raster.
inline void PrefetchDepthPixel(const SacView& view, int row, int col) { __builtin_prefetch(&view.depth->at(row, col)); }
// Where a world point falls in a view: its depth there and its image coordinates in the depth raster (corner
// convention). Only `in_front` is meaningful when it is false (the point lies behind the view).
struct ViewPoint {
  bool in_front;
  double z_m;
  Eigen::Vector2d uv;
};
inline ViewPoint ProjectIntoView(const SacView& view, const Eigen::Vector3d& point_in_world) {
  const Eigen::Vector3d p = view.PointInCamera(point_in_world);
  if (p.z() <= 0) return {false, 0.0, Eigen::Vector2d::Zero()};
  return {true, p.z(), view.depth_camera.Project(p)};
}
// The 2 x 2 pixels around `at` (a bilinear sample, SampleDepth in core/depth_combine.h). Nothing when the point is
// behind the view or outside its raster.
inline void PrefetchDepthAround(const SacView& view, const ViewPoint& at) {
  if (!at.in_front) return;
  // Pixel centres at +0.5: the sample's top-left pixel, clamped so that its 2 x 2 block lies inside.
  const double x = at.uv.x() - 0.5, y = at.uv.y() - 0.5;
  const DepthMap& depth = *view.depth;
  if (!(x >= -1.0 && y >= -1.0 && x < depth.width && y < depth.height)) return;
  const int col = std::clamp(static_cast<int>(std::floor(x)), 0, depth.width - 1);
  const int row = std::clamp(static_cast<int>(std::floor(y)), 0, std::max(0, depth.height - 2));
  PrefetchDepthPixel(view, row, col);
  if (row + 1 < depth.height) PrefetchDepthPixel(view, row + 1, col);
}

// The colour of depth pixel (row, col): the image pixel under its centre (the image may have another resolution
// than the depth raster); mid grey when the view has no image.
std::array<uint8_t, 3> PixelColour(const SacView& view, int row, int col);
// The same with the image given apart from the view (null = grey).
std::array<uint8_t, 3> PixelColour(const RgbImage* image, const DepthMap& depth, int row, int col);

}  // namespace sacfuse
