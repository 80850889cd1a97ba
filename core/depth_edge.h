#pragma once
// Foreground depth edges: where a surface in a depth map ends in front of a much deeper one (a roof edge over the
// street, a crown over the ground). Stereo matchers spread the foreground a few pixels over the background there
// (fattening) and invalidate a band behind it (left-right check), so the pixels next to such an edge are the ones
// whose depth is least to be trusted, and the deeper surface may lie several pixels away beyond a band of holes.
#include "core/pixel_window.h"
#include "core/raster.h"

namespace sacfuse {

// Whether any depth of the square window of `radius` pixels around (row, col), clipped to the raster, satisfies
// `test` (called with the stored float depth, invalid ones included).
template <typename Test>
bool AnyDepthInWindow(const DepthMap& depth, int row, int col, int radius, Test test) {
  const PixelWindow w = SquareAround(row, col, radius, depth.width, depth.height);
  for (int r = w.row_begin; r < w.row_end; ++r) {
    for (int c = w.col_begin; c < w.col_end; ++c) {
      if (test(depth.at(r, c))) return true;
    }
  }
  return false;
}

// How far from a pixel a deeper surface is searched for, pixels: the fattening and the invalid band behind it
// (1-3 and 2-4 pixels in aerial-bench's depth maps, 2 and 3 in `sacfuse simulate`'s).
constexpr int kDepthEdgeReachPx = 7;

// Whether pixel (row, col) of `depth`, whose depth is `depth_m`, lies within `band_px` pixels (a square window) of
// an invalid pixel or of one more than `jump_m` deeper, and within kDepthEdgeReachPx pixels of a valid one more than
// `jump_m` deeper: the outer band of a foreground surface. False for band_px <= 0. Pixels off the raster count as
// neither (the image border is not an edge).
bool OnForegroundEdge(const DepthMap& depth, int row, int col, double depth_m, double jump_m, int band_px);

}  // namespace sacfuse
