#pragma once
// The combine (core/depth_combine.h) at anchor pixels, interpolated between them (`fusion.combine_anchors`, issue
// 13). The combine reads ~36 other depth maps twice for every emitted pixel: ~40 % of SAC's time on a full-scale
// Dortmund tile (perf). What it adds to a pixel's own depth d is the other depth maps' weighted mean surface M on
// the pixel's ray and their summed weight W: depth = (w_own d + W M) / (w_own + W). M and W vary smoothly over a
// surface; d carries the pixel's own noise. So within a patch of the collapse:
//  1. the emitted pixels an even number of rows and columns from the patch's first pixel are combined exactly;
//  2. every other emitted pixel, in row order, takes M and W from the exactly combined pixels among its 8
//     neighbours (at least kMinAnchorNeighbours, each one's M carried along the plane of the pixel's superpixel
//     onto its ray, as the combine carries a neighbour view's surface point; M and W averaged), and its own d;
//  3. it is combined exactly instead (and then serves its later neighbours as an anchor) when fewer neighbours
//     were combined exactly (the emitted set is ragged where views take turns), when their surfaces on its ray
//     differ by more than max(kAnchorToleranceGsd local GSDs, kAnchorToleranceSigmas sigma of its own depth's
//     estimated noise) (a depth edge, a step, a twisted surface), or when d lies outside the combine's gate of M.
// An anchor where no other depth map agreed does not count. Measured (docs/design.md): a
// full-scale Dortmund tile 0.84x the CPU time (half of its emitted pixels interpolated); F1 at 2x GSD within
// +-0.0007 on the six aerial-bench blocks and 0.02-0.43 points higher on our six bench blocks (M averaged over
// neighbouring rays is less noisy); 1 neighbour instead of 2 (no consistency check) lost 0.001-0.002 at error
// scale 2.5.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/depth_combine.h"
#include "core/pixel_window.h"
#include "core/sac_view.h"

namespace sacfuse {

inline constexpr int kMinAnchorNeighbours = 2;
inline constexpr double kAnchorToleranceGsd = 1.0;
inline constexpr double kAnchorToleranceSigmas = 1.0;

// The exactly combined pixels of one patch and what the other depth maps gave each.
class CombineAnchors {
 public:
  explicit CombineAnchors(const PixelWindow& patch);

  // Whether pixel (row, col) of the patch is combined exactly whatever its neighbours (step 1 of the header).
  bool IsAnchor(int row, int col) const { return (((row - patch_.row_begin) | (col - patch_.col_begin)) & 1) == 0; }
  // Records the exact combine of pixel (row, col) of the patch.
  void Set(int row, int col, const CombinedDepth& combined);

  // The combined depth of pixel (row, col) of `views[v]` with own depth `depth_m` from its exactly combined
  // neighbours (steps 2 and 3 of the header); false when it must be combined exactly. `plane_normal_in_world`: the
  // plane of the pixel's superpixel (zero = none: the neighbours' M are averaged as they are).
  bool Interpolate(const std::vector<SacView>& views, uint32_t v, int row, int col, double depth_m,
                   const std::vector<double>& noise_factor, const DepthCombineOptions& options,
                   const Eigen::Vector3d& plane_normal_in_world, double* combined_depth_m) const;

 private:
  struct Anchor {
    bool valid = false;           // combined exactly, and at least one other depth map agreed
    double others_depth_m = 0.0;  // CombinedDepth::others_depth_m
    double others_weight = 0.0;   // CombinedDepth::others_weight
  };
  const Anchor* At(int row, int col) const;

  PixelWindow patch_;
  std::vector<Anchor> anchors_;  // per pixel of the patch, row-major
};

}  // namespace sacfuse
