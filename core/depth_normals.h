#pragma once
// Surface normals computed from a depth raster alone (for methods that compare normals, like fusibile's
// disparity-and-normal consistency, when the input's normal maps are not used): a least-squares plane through
// the back-projected pixels of a (2r+1) x (2r+1) window, pixels on another surface excluded.
#include <atomic>
#include <cstdint>
#include <memory>

#include <Eigen/Core>

#include "core/raster.h"
#include "core/sac_view.h"

namespace sacfuse {

// Unit normals in the WORLD frame, one per depth pixel (3 channels), facing the view's camera; (0, 0, 0) where
// the pixel is invalid or fewer than 5 window pixels lie on its surface. A window pixel counts when its depth is
// within 3 local GSDs per pixel of distance (Chebyshev, plus one) of the centre's depth, so depth edges do not
// tilt the normals of either side. The plane is the eigenvector of the smallest eigenvalue of the points'
// covariance (camera frame, relative to the centre pixel's point). Parallel over rows; deterministic.
NormalMap PlaneFitNormalsInWorld(const SacView& view, int radius_px);

// The same normals, each computed when first asked for: for a caller that reads a small share of the pixels
// (co-registration reads a neighbour's normal only where one of its samples lands). At() may
// be called from many threads at once: a pixel is stored by the first thread that claims it, and a thread that
// finds it unclaimed or being stored computes its own copy, which is equal (the fit is deterministic). The view's
// depth raster must outlive this object; the frame is the view's pose at construction.
class LazyPlaneFitNormals {
 public:
  LazyPlaneFitNormals() = default;
  LazyPlaneFitNormals(const SacView& view, int radius_px);
  // The normal of depth pixel (row, col), as PlaneFitNormalsInWorld gives it: (0, 0, 0) where it has none.
  Eigen::Vector3f At(int row, int col) const;

 private:
  enum : uint8_t { kEmpty = 0, kWriting = 1, kReady = 2 };
  const DepthMap* depth_ = nullptr;
  PinholeCamera camera_;
  Eigen::Matrix3d world_from_cam_rot_ = Eigen::Matrix3d::Identity();
  int radius_px_ = 1;
  std::unique_ptr<std::atomic<uint8_t>[]> state_;  // per pixel; kReady: normals_ holds it
  std::unique_ptr<float[]> normals_;               // 3 per pixel, written once by the claiming thread
};

}  // namespace sacfuse
