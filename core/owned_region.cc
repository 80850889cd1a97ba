#include "core/owned_region.h"

#include <algorithm>
#include <limits>

#include "core/method_views.h"
#include "core/patch_grid.h"

namespace sacfuse {
namespace {

// Decisions on the corners' box keep this distance from the region's edges, metres: the corners and the pixels'
// points are computed in double with rounding errors of ~1e-9 m at UTM coordinates.
constexpr double kMarginM = 1e-3;
// CountOwnedPixels' patches, pixels: the collapse's size (core/collapse.cc), small enough that most lie wholly inside
// or outside a tile.
constexpr int kCountPatchRows = 32;
constexpr int kCountPatchCols = 64;

}  // namespace

WindowOwnership ClassifyWindow(const SacView& view, const PixelWindow& window, const OwnedRegion& region) {
  WindowOwnership out;
  const DepthMap& depth = *view.depth;
  float min_depth = std::numeric_limits<float>::infinity(), max_depth = 0.0f;
  for (int row = window.row_begin; row < window.row_end; ++row) {
    for (int col = window.col_begin; col < window.col_end; ++col) {
      const float d = depth.at(row, col);
      if (!IsValidDepth(d)) continue;
      ++out.valid_pixels;
      min_depth = std::min(min_depth, d);
      max_depth = std::max(max_depth, d);
    }
  }
  if (out.valid_pixels == 0) return out;
  if (region.OwnsEverything()) {
    out.kind = WindowOwnership::kAll;
    return out;
  }
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(OwnedRegion::kInfinity), hi = -lo;
  for (const int row : {window.row_begin, window.row_end - 1}) {
    for (const int col : {window.col_begin, window.col_end - 1}) {
      for (const float d : {min_depth, max_depth}) {
        const Eigen::Vector2d xy = PixelPoint(view, row, col, d).head<2>();
        lo = lo.cwiseMin(xy);
        hi = hi.cwiseMax(xy);
      }
    }
  }
  const bool inside = (lo.array() >= region.min.array() + kMarginM).all() &&
                      (hi.array() < region.max.array() - kMarginM).all();
  const bool outside = (hi.array() < region.min.array() - kMarginM).any() ||
                       (lo.array() >= region.max.array() + kMarginM).any();
  out.kind = inside ? WindowOwnership::kAll : outside ? WindowOwnership::kNone : WindowOwnership::kSome;
  return out;
}

size_t CountOwnedPixels(const SacView& view, const OwnedRegion& region) {
  const DepthMap& depth = *view.depth;
  const PatchGrid grid(depth.height, depth.width, kCountPatchRows, kCountPatchCols);
  size_t owned = 0;
  for (int p = 0; p < grid.size(); ++p) {
    const PixelWindow patch = grid.Patch(p);
    const WindowOwnership ownership = ClassifyWindow(view, patch, region);
    if (ownership.kind == WindowOwnership::kAll) owned += ownership.valid_pixels;
    if (ownership.kind != WindowOwnership::kSome) continue;
    for (int row = patch.row_begin; row < patch.row_end; ++row) {
      for (int col = patch.col_begin; col < patch.col_end; ++col) {
        const float d = depth.at(row, col);
        if (IsValidDepth(d) && region.Contains(PixelPoint(view, row, col, d))) ++owned;
      }
    }
  }
  return owned;
}

}  // namespace sacfuse
