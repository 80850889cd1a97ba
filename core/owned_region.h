#pragma once
// Which pixels a run owns, judged on each pixel's own back-projected point: a tile's core, an XY box. Every pixel of
// a tiled run is owned by exactly one tile (tiling/tile_grid.h).
//
// At Dortmund scale a tile's windows hold ~3x the pixels its core owns (oblique views, halo), and testing each
// pixel's point cost ~5 % of a tile (issue 13). A pinhole pixel's points over a patch of pixels and a depth range
// fill a truncated pyramid, the convex hull of its 8 corners, so a patch whose corners all lie well inside the box
// is owned whole, one whose corners all lie well outside it is not owned at all, and only the patches across the
// box's edges are tested pixel by pixel; the answer is that of testing every pixel.
#include <cstddef>
#include <cstdint>
#include <limits>

#include <Eigen/Core>

#include "core/pixel_window.h"
#include "core/sac_view.h"

namespace sacfuse {

// A half-open XY box [min, max) in world metres whose sides may be infinite (a border tile also owns what lies
// beyond the grid). The default owns every point.
struct OwnedRegion {
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  Eigen::Vector2d min{-kInfinity, -kInfinity};  // inclusive
  Eigen::Vector2d max{kInfinity, kInfinity};    // exclusive

  bool OwnsEverything() const {
    return min.x() == -kInfinity && min.y() == -kInfinity && max.x() == kInfinity && max.y() == kInfinity;
  }
  bool Contains(const Eigen::Vector3d& point_in_world) const {
    return point_in_world.x() >= min.x() && point_in_world.x() < max.x() && point_in_world.y() >= min.y() &&
           point_in_world.y() < max.y();
  }
};

// How the valid depth pixels of a window of a view lie in a region.
struct WindowOwnership {
  enum Kind : uint8_t { kNone, kAll, kSome };
  Kind kind = kNone;        // kSome: test each pixel with OwnedRegion::Contains
  size_t valid_pixels = 0;  // valid depth pixels in the window
};
WindowOwnership ClassifyWindow(const SacView& view, const PixelWindow& window, const OwnedRegion& region);

// Valid depth pixels of `view` whose own point `region` owns (ClassifyWindow over patches, then per pixel).
size_t CountOwnedPixels(const SacView& view, const OwnedRegion& region);

}  // namespace sacfuse
