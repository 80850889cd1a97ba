#include "core/depth_edge.h"

#include <algorithm>

namespace sacfuse {

bool OnForegroundEdge(const DepthMap& depth, int row, int col, double depth_m, double jump_m, int band_px) {
  if (band_px <= 0) return false;
  const double deeper_than = depth_m + jump_m;
  const bool at_boundary = AnyDepthInWindow(depth, row, col, band_px,
                                            [&](float q) { return !IsValidDepth(q) || q > deeper_than; });
  return at_boundary && AnyDepthInWindow(depth, row, col, std::max(band_px, kDepthEdgeReachPx),
                                         [&](float q) { return IsValidDepth(q) && q > deeper_than; });
}

}  // namespace sacfuse
