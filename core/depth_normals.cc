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

// The normal of pixel (row, col) by the rule of depth_normals.h, rotated by world_from_cam_rot; zero where the
// pixel is invalid or too few window pixels lie on its surface.
Eigen::Vector3f NormalAt(const DepthMap& depth, const PinholeCamera& cam, const Eigen::Matrix3d& world_from_cam_rot,
                         int row, int col, int radius_px) {
  const float dc = depth.at(row, col);
  if (!IsValidDepth(dc)) return Eigen::Vector3f::Zero();
  const Eigen::Vector3d centre = DepthPixelInCamera(cam, col, row, dc);
  const double gsd = dc / cam.fx;  // SacView::GsdAt
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
  if (plane.count() < kMinPlanePixels) return Eigen::Vector3f::Zero();
  Eigen::Vector3d n = plane.Normal();
  if (n.dot(centre) > 0) n = -n;  // face the camera
  return (world_from_cam_rot * n).normalized().cast<float>();
}

}  // namespace

NormalMap PlaneFitNormalsInWorld(const SacView& view, int radius_px) {
  const DepthMap& depth = *view.depth;
  NormalMap normals(depth.width, depth.height, 3, 0.0f);
  const Eigen::Matrix3d world_from_cam_rot = view.world_from_cam.rotation.toRotationMatrix();
  tbb::parallel_for(0, depth.height, [&](int row) {
    for (int col = 0; col < depth.width; ++col) {
      const Eigen::Vector3f n = NormalAt(depth, view.depth_camera, world_from_cam_rot, row, col, radius_px);
      for (int k = 0; k < 3; ++k) normals.at(row, col, k) = n[k];
    }
  });
  return normals;
}

LazyPlaneFitNormals::LazyPlaneFitNormals(const SacView& view, int radius_px)
    : depth_(view.depth),
      camera_(view.depth_camera),
      world_from_cam_rot_(view.world_from_cam.rotation.toRotationMatrix()),
      radius_px_(radius_px),
      state_(new std::atomic<uint8_t>[depth_->num_pixels()]()),
      normals_(new float[3 * depth_->num_pixels()]) {}

Eigen::Vector3f LazyPlaneFitNormals::At(int row, int col) const {
  const size_t i = static_cast<size_t>(row) * static_cast<size_t>(depth_->width) + static_cast<size_t>(col);
  float* stored = normals_.get() + 3 * i;
  if (state_[i].load(std::memory_order_acquire) == kReady) return Eigen::Vector3f(stored[0], stored[1], stored[2]);
  const Eigen::Vector3f n = NormalAt(*depth_, camera_, world_from_cam_rot_, row, col, radius_px_);
  uint8_t expected = kEmpty;  // the first thread to claim the pixel stores it; others return their own, equal copy
  if (state_[i].compare_exchange_strong(expected, kWriting, std::memory_order_relaxed)) {
    for (int k = 0; k < 3; ++k) stored[k] = n[k];
    state_[i].store(kReady, std::memory_order_release);
  }
  return n;
}

}  // namespace sacfuse
