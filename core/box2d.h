#pragma once
// The one axis-aligned 2-D box of sacfuse (world XY, metres, unless a caller says otherwise): footprints, tile
// cores and halos, report strips, simulated scene areas.
//
// A box is closed: it contains its edges. Two rules about "empty" are kept apart on purpose:
//   IsEmpty()  nothing was added (min > max on an axis); a box of one point or one line is not empty,
//   HasArea()  positive width and height, what areas, overlaps and neighbour scores need.
#include <algorithm>
#include <limits>

#include <Eigen/Core>

namespace sacfuse {

struct Box2d {
  Eigen::Vector2d min = Eigen::Vector2d::Constant(1e300);   // a default box is empty
  Eigen::Vector2d max = Eigen::Vector2d::Constant(-1e300);

  Box2d() = default;
  Box2d(double x0, double y0, double x1, double y1) : min(x0, y0), max(x1, y1) {}
  Box2d(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) : min(lo), max(hi) {}
  // Unbounded in every direction.
  static Box2d Infinite() {
    const double inf = std::numeric_limits<double>::infinity();
    return Box2d(-inf, -inf, inf, inf);
  }

  bool IsEmpty() const { return min.x() > max.x() || min.y() > max.y(); }
  bool HasArea() const { return min.x() < max.x() && min.y() < max.y(); }
  double Width() const { return max.x() - min.x(); }
  double Height() const { return max.y() - min.y(); }
  double Area() const { return HasArea() ? Width() * Height() : 0.0; }
  Eigen::Vector2d Center() const { return 0.5 * (min + max); }

  void Extend(const Eigen::Vector2d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void Extend(const Box2d& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  bool Contains(const Eigen::Vector2d& p) const { return Contains(p.x(), p.y()); }
  bool Contains(double x, double y) const { return x >= min.x() && y >= min.y() && x <= max.x() && y <= max.y(); }
  // Closed boxes: touching edges intersect.
  bool Intersects(const Box2d& b) const {
    return !(b.min.x() > max.x() || b.max.x() < min.x() || b.min.y() > max.y() || b.max.y() < min.y());
  }
  // The common part (IsEmpty() when the boxes do not meet).
  Box2d Intersection(const Box2d& b) const { return Box2d(min.cwiseMax(b.min), max.cwiseMin(b.max)); }
  Box2d Expanded(double margin) const {
    return Box2d(min - Eigen::Vector2d::Constant(margin), max + Eigen::Vector2d::Constant(margin));
  }
};

// Area of the common part of two boxes (0 when it has no area).
inline double OverlapArea(const Box2d& a, const Box2d& b) { return a.Intersection(b).Area(); }

}  // namespace sacfuse
