#include "eval/top_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace sacfuse {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
}  // namespace

TopSurface::TopSurface(const std::vector<Eigen::Vector3f>& reference, double cell_m, size_t max_cells)
    : cell_(cell_m) {
  if (!(cell_m > 0.0)) throw Error("TopSurface: cell size must be > 0");
  if (reference.empty()) return;
  Eigen::Vector2f lo = reference[0].head<2>(), hi = lo;
  for (const auto& p : reference) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  x0_ = lo.x();
  y0_ = lo.y();
  nx_ = static_cast<int64_t>(std::floor((hi.x() - lo.x()) / cell_)) + 1;
  ny_ = static_cast<int64_t>(std::floor((hi.y() - lo.y()) / cell_)) + 1;
  const double cells = static_cast<double>(nx_) * static_cast<double>(ny_);
  if (cells > static_cast<double>(max_cells)) {
    throw Error("reference extent " + std::to_string(hi.x() - lo.x()) + " x " + std::to_string(hi.y() - lo.y()) +
                " m needs " + std::to_string(static_cast<uint64_t>(cells)) + " top-surface cells of " +
                std::to_string(cell_) + " m (limit " + std::to_string(max_cells) +
                "); raise top_cell_m or evaluate tile by tile");
  }
  top_.assign(static_cast<size_t>(nx_ * ny_), -kInf);
  bottom_.assign(static_cast<size_t>(nx_ * ny_), kInf);
  for (const auto& p : reference) {
    const int64_t cx = std::clamp<int64_t>(static_cast<int64_t>(std::floor((p.x() - x0_) / cell_)), 0, nx_ - 1);
    const int64_t cy = std::clamp<int64_t>(static_cast<int64_t>(std::floor((p.y() - y0_) / cell_)), 0, ny_ - 1);
    const size_t k = static_cast<size_t>(cy * nx_ + cx);
    top_[k] = std::max(top_[k], p.z());
    bottom_[k] = std::min(bottom_[k], p.z());
  }
  occupied_ = static_cast<size_t>(std::count_if(top_.begin(), top_.end(), [](float t) { return t > -kInf; }));
}

float TopSurface::TopAt(int64_t cx, int64_t cy) const {
  if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return -kInf;
  return top_[static_cast<size_t>(cy * nx_ + cx)];
}

TopSurface::Column TopSurface::Query(float x, float y) const {
  Column c;
  if (nx_ == 0) return c;
  const double fx = std::floor((x - x0_) / cell_), fy = std::floor((y - y0_) / cell_);
  // Far outside the grid: no reference there (also guards the integer conversion).
  if (fx < -2.0 || fy < -2.0 || fx > static_cast<double>(nx_) + 1.0 || fy > static_cast<double>(ny_) + 1.0) return c;
  const int64_t cx = static_cast<int64_t>(fx), cy = static_cast<int64_t>(fy);
  float top = -kInf, bottom = kInf;
  for (int64_t dy = -1; dy <= 1; ++dy) {
    for (int64_t dx = -1; dx <= 1; ++dx) {
      const int64_t ix = cx + dx, iy = cy + dy;
      if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) continue;
      const size_t k = static_cast<size_t>(iy * nx_ + ix);
      top = std::max(top, top_[k]);
      bottom = std::min(bottom, bottom_[k]);
    }
  }
  if (top == -kInf) return c;
  c.observed = true;
  c.top = top;
  c.bottom = bottom;
  float occ = TopAt(cx, cy);
  occ = std::max(occ, std::min(TopAt(cx - 1, cy), TopAt(cx + 1, cy)));
  occ = std::max(occ, std::min(TopAt(cx, cy - 1), TopAt(cx, cy + 1)));
  occ = std::max(occ, std::min(TopAt(cx - 1, cy - 1), TopAt(cx + 1, cy + 1)));
  occ = std::max(occ, std::min(TopAt(cx - 1, cy + 1), TopAt(cx + 1, cy - 1)));
  c.occluder = occ;  // may be -inf when only diagonal/one-sided neighbours hold points (nothing hides the column)
  return c;
}

}  // namespace sacfuse
