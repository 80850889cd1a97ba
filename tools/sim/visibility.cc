#include "tools/sim/visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

namespace sacfuse::sim {

bool SeesPoint(const DepthMap& depth, const PinholeCamera& cam, const Rigid3d& cam_from_world,
               const Eigen::Vector3d& point) {
  const Eigen::Vector3d pc = cam_from_world * point;
  if (pc.z() <= 0.0) return false;
  const Eigen::Vector2d uv = cam.Project(pc);
  if (!(uv.x() >= 0.0 && uv.y() >= 0.0 && uv.x() < cam.width && uv.y() < cam.height)) return false;
  const double tol = 0.05 + 1.5 * pc.z() / std::min(cam.fx, cam.fy);
  const int c0 = static_cast<int>(std::floor(uv.x() - 0.5)), r0 = static_cast<int>(std::floor(uv.y() - 0.5));
  for (int r = r0; r <= r0 + 1; ++r) {
    for (int c = c0; c <= c0 + 1; ++c) {
      if (!depth.Contains(r, c)) continue;
      const float d = depth.at(r, c);
      if (IsValidDepth(d) && std::abs(d - pc.z()) <= tol) return true;
    }
  }
  return false;
}

double EvalCellSize(double requested_m, const Box2d& area) {
  if (requested_m > 0.0) return requested_m;
  double cell = 1.0;
  const double side = std::min(area.Width(), area.Height());
  while (cell > 0.25 && side / cell < 100.0) cell *= 0.5;
  return cell;
}

CoverageCounter::CoverageCounter(const Surface& surface, const Box2d& area, double cell_m)
    : area_(area), cell_(cell_m) {
  width_ = std::max(1, static_cast<int>(std::ceil(area.Width() / cell_ - 1e-9)));
  height_ = std::max(1, static_cast<int>(std::ceil(area.Height() / cell_ - 1e-9)));
  const size_t n = static_cast<size_t>(width_) * height_;
  heights_.resize(n);
  counts_.assign(n, 0);
  base_z_ = surface.GlobalRange().IsEmpty() ? 0.0 : surface.GlobalRange().lo;
  tbb::parallel_for(0, height_, [&](int row) {
    for (int col = 0; col < width_; ++col) {
      const double x = area_.min.x() + (col + 0.5) * cell_, y = area_.max.y() - (row + 0.5) * cell_;
      const double z = surface.Height(x, y);
      heights_[static_cast<size_t>(row) * width_ + col] =
          std::isfinite(z) ? static_cast<float>(z - base_z_) : std::numeric_limits<float>::quiet_NaN();
    }
  });
}

void CoverageCounter::AddView(const DepthMap& depth, const PinholeCamera& cam, const Rigid3d& cam_from_world) {
  tbb::parallel_for(0, height_, [&](int row) {
    for (int col = 0; col < width_; ++col) {
      const size_t i = static_cast<size_t>(row) * width_ + col;
      if (std::isnan(heights_[i]) || counts_[i] == 255) continue;
      const Eigen::Vector3d p(area_.min.x() + (col + 0.5) * cell_, area_.max.y() - (row + 0.5) * cell_, base_z_ + heights_[i]);
      if (SeesPoint(depth, cam, cam_from_world, p)) ++counts_[i];
    }
  });
}

GeoMask CoverageCounter::Mask(int min_views) const {
  GeoMask mask;
  mask.origin_x = area_.min.x();
  mask.origin_y = area_.max.y();
  mask.cell_size_m = cell_;
  mask.width = width_;
  mask.height = height_;
  mask.cells.resize(counts_.size());
  for (size_t i = 0; i < counts_.size(); ++i) mask.cells[i] = counts_[i] >= min_views ? 1 : 0;
  return mask;
}

double CoverageCounter::FractionSeen(int min_views) const {
  size_t defined = 0, seen = 0;
  for (size_t i = 0; i < counts_.size(); ++i) {
    if (std::isnan(heights_[i])) continue;
    ++defined;
    seen += counts_[i] >= min_views ? 1 : 0;
  }
  return defined == 0 ? 0.0 : static_cast<double>(seen) / defined;
}

}  // namespace sacfuse::sim
