#include "core/depth_normals.h"

#include "core/backproject.h"
#include "core/pixel_window.h"
#include "core/plane_fit.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace sacfuse {
namespace {

constexpr double kStepGsdPerPixel = 3.0;
constexpr int kMinPlanePixels = 5;

}  // namespace

NormalMap PlaneFitNormalsInWorld(const SacView& view, int radius_px) {
  const DepthMap& depth = *view.depth;
  NormalMap normals(depth.width, depth.height, 3, 0.0f);
  const PinholeCamera& cam = view.depth_camera;
  const Eigen::Matrix3d world_from_cam_rot = view.world_from_cam.rotation.toRotationMatrix();
  tbb::parallel_for(0, depth.height, [&](int row) {
    for (int col = 0; col < depth.width; ++col) {
      const float dc = depth.at(row, col);
      if (!IsValidDepth(dc)) continue;
      const Eigen::Vector3d centre = DepthPixelInCamera(cam, col, row, dc);
      const double gsd = view.GsdAt(dc);
      PlaneFit plane;
      const PixelWindow window = SquareAround(row, col, radius_px, depth.width, depth.height);
      for (int r = window.row_begin; r < window.row_end; ++r) {
        for (int c = window.col_begin; c < window.col_end; ++c) {
          const float d = depth.at(r, c);
          if (!IsValidDepth(d)) continue;
          const int steps = std::max(std::abs(r - row), std::abs(c - col)) + 1;
          if (std::abs(d - dc) > kStepGsdPerPixel * gsd * steps) continue;
          plane.Add(DepthPixelInCamera(cam, c, r, d) - centre);
        }
      }
      if (plane.count() < kMinPlanePixels) continue;
      Eigen::Vector3d n = plane.Normal();
      if (n.dot(centre) > 0) n = -n;  // face the camera
      const Eigen::Vector3d w = (world_from_cam_rot * n).normalized();
      for (int k = 0; k < 3; ++k) normals.at(row, col, k) = static_cast<float>(w[k]);
    }
  });
  return normals;
}

}  // namespace sacfuse
