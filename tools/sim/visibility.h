#pragma once
// Which views see which surface points, decided per view while its TRUE depth map is in memory (streaming).
// A point is seen when it projects inside the depth raster, in front of the camera, and one of the (up to four)
// pixels around its projection has a true depth within tol = 0.05 m + 1.5 pixel footprints (z / f) of the
// point's depth: an occluder in front makes the difference large.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/camera.h"
#include "core/geo_mask.h"
#include "core/raster.h"
#include "core/rigid3.h"
#include "tools/sim/surface.h"

namespace sacfuse::sim {

bool SeesPoint(const DepthMap& true_depth, const PinholeCamera& depth_camera, const Rigid3d& true_cam_from_world,
               const Eigen::Vector3d& point);

// The evaluation mask: per cell of `cell_m` over `area`, how many views see the true surface point at the cell
// centre; cells seen by >= min_views are inside.
class CoverageCounter {
 public:
  CoverageCounter(const Surface& surface, const Box2d& area, double cell_m);
  void AddView(const DepthMap& true_depth, const PinholeCamera& depth_camera, const Rigid3d& true_cam_from_world);
  GeoMask Mask(int min_views) const;
  // Fraction of cells (with a defined surface) seen by >= min_views.
  double FractionSeen(int min_views) const;
  int width() const { return width_; }
  int height() const { return height_; }
  uint8_t count(int row, int col) const { return counts_[static_cast<size_t>(row) * width_ + col]; }

 private:
  Box2d area_;
  double cell_;
  int width_ = 0, height_ = 0;
  std::vector<float> heights_;  // relative to base_z_, NaN where undefined
  double base_z_ = 0.0;
  std::vector<uint8_t> counts_;
};

// Eval-mask cell: explicit, else 1 m halved while the shorter area side has fewer than 100 cells (>= 0.25 m).
double EvalCellSize(double requested_m, const Box2d& area);

}  // namespace sacfuse::sim
