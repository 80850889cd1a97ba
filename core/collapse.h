#pragma once
// Netlet collapse (Section III.B, "combine"): every pixel takes its cluster's label; same-labelled nodes collapse
// onto the points of the selected view.
//
// Coverage rule (the paper is silent): a pixel of view a whose cluster chose view L != a is dropped only when a
// view actually emits that surface: the pixel's point projects into L onto a valid depth that agrees with it (within
// the tolerance, or — with estimated noise — within coverage_tolerance_sigmas sigma of the two depths' difference), and
// the cluster there chose L itself — or chose L2, and the same holds in L2 (up to 4 hops, never back to a).
// Otherwise the pixel is emitted from its own view. So no surface patch observed consistently is lost.
// Outliers: an emitted point must agree with min(min_consistent_views, max(2, 1 + observers)) depth maps (its own
// included) among its view's neighbours, where observers are the neighbours that agree or see through the point
// (free space); neighbours in which it is occluded cannot judge it. So blunders, floaters and points seen by one
// view only are removed, while surfaces that only two views can see are kept when those two agree. With estimated
// noise (combine: average) the requirement is also capped at max(2, 1 + round(outlier_expected_factor x E)), E the
// expected number of agreeing observers, sum of erf(tolerance / (sqrt(2) sigma of the two depths' difference)):
// low-noise blocks keep the strict count, noisy ones are not asked for agreement the noise does not allow.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/point.h"
#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct CollapseStats {
  uint64_t input_pixels = 0;      // valid depth pixels (that the owner accepts)
  uint64_t collapsed = 0;         // dropped: covered by the view their cluster chose
  uint64_t kept_uncovered = 0;    // their cluster chose another view, which does not emit them: kept (coverage)
  uint64_t outliers = 0;          // dropped: too few consistent views
  uint64_t emitted = 0;
  uint64_t not_owned = 0;         // valid pixels the owner rejected (another tile's), not counted above
  CollapseStats& operator+=(const CollapseStats& o) {
    input_pixels += o.input_pixels;
    collapsed += o.collapsed;
    kept_uncovered += o.kept_uncovered;
    outliers += o.outliers;
    emitted += o.emitted;
    not_owned += o.not_owned;
    return *this;
  }
};

// Emits the fused points of view `v` to `sink` in row order (deterministic for any thread count). `neighbors`
// judge outliers; `combine_views` (fusion.combine: average) refine the emitted depths, weighted with the views'
// `noise_factor` (core/view_noise.h; empty = equal). Pixels whose own point `owner` rejects are skipped and not
// counted (empty owner = all pixels).
CollapseStats EmitView(uint32_t v, const std::vector<SacView>& views, const NodeTable& nodes,
                       const std::vector<uint32_t>& chosen_view, const std::vector<std::vector<uint32_t>>& neighbors,
                       const std::vector<std::vector<uint32_t>>& combine_views,
                       const std::vector<double>& noise_factor, const SacOptions& options,
                       const std::function<bool(const Eigen::Vector3d&)>& owner, PointSink& sink);

}  // namespace sacfuse
