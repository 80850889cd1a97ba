#pragma once
// SAC's tests of every depth pixel's own point X against the other views, made once per pixel before the collapse
// (core/collapse.h) so that the collapse knows which pixels of other views will be emitted: a pixel is dropped in
// favour of another view only where that view's pixel survives these tests, so removing outliers never leaves a
// hole that another view's pixel would have filled.
//
//  * Outliers (the paper is silent): X must agree with min(min_consistent_views, max(2, 1 + observers)) depth maps
//    (its own included) among its view's neighbours, where observers are the neighbours that agree or see through
//    the point; neighbours in which it is occluded cannot judge it. With estimated noise the requirement is also
//    capped at max(2, 1 + round(outlier_expected_factor x E)), E = the expected number of agreeing observers, sum of
//    erf(tolerance / (sqrt(2) sigma of the two depths' difference)).
//  * Free space (visibility, Merrell et al., ICCV 2007): X is dropped when at least free_space_min_views of the
//    judging views (the combine views, up to 40) see through it: their depth at X's projection lies beyond X by more
//    than the tolerance and more than free_space_sigmas sigma of the two depths' difference, so X floats in space
//    they observed empty (fattened foreground at depth jumps, blunders, noisy canopy). Measured on aerial-bench
//    Montpellier (README): asking also that more views see through X than agree with it removed nothing.
#include <cstdint>
#include <vector>

#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

enum class PointVerdict : uint8_t { kInvalid = 0, kOutlier = 1, kFreeSpace = 2, kPasses = 3 };

// One verdict per depth pixel of each view (row-major, the view's depth raster), for every valid pixel of every
// loaded view (a tile's halo pixels too: the collapse consults them). `judges[v]`: the views that judge free space
// for view v. Deterministic for any thread count.
struct PointVerdicts {
  std::vector<std::vector<PointVerdict>> per_view;
  PointVerdict At(uint32_t view, const DepthMap& depth, int row, int col) const {
    return per_view[view][static_cast<size_t>(row) * depth.width + col];
  }
};

PointVerdicts JudgePoints(const std::vector<SacView>& views, const std::vector<std::vector<uint32_t>>& neighbors,
                          const std::vector<std::vector<uint32_t>>& judges, const std::vector<double>& noise_factor,
                          const SacOptions& options);

}  // namespace sacfuse
