#pragma once
// Netlet collapse (Section III.B, "combine"): every pixel takes its cluster's label; same-labelled nodes collapse
// onto the points of the selected view.
//
// Coverage rule (the paper is silent): a pixel of view a whose cluster chose view L != a is dropped only when a
// view actually emits that surface: the pixel's point projects into L onto a valid depth that agrees with it (within
// the tolerance, or — with estimated noise — within coverage_tolerance_sigmas sigma of the two depths' difference), and
// the cluster there chose L itself — or chose L2, and the same holds in L2 (up to 4 hops, never back to a).
// Otherwise the pixel is emitted from its own view. So no surface patch observed consistently is lost.
// With `collapse: best_view` so are pixels a more precise view emits (core/redundancy.h); with `collapse: none` no
// pixel is dropped for another view (neither test is made, so no Netlet is labelled). A pixel that is not dropped
// in favour of another view is emitted when it passes its own outlier and free-space tests (core/point_verdicts.h);
// the other view's pixel must pass them too, so no pixel is dropped in favour of an outlier.
#include <cstdint>
#include <vector>

#include "core/consulted_views.h"
#include "core/owned_region.h"
#include "core/point.h"
#include "core/point_verdicts.h"
#include "core/sac_labeling.h"
#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct CollapseStats {
  uint64_t input_pixels = 0;      // valid depth pixels (that the owner accepts)
  // A pixel dropped for another view is counted once, in the first test that drops it, in this order:
  uint64_t redundant = 0;         // dropped: a more precise view holds the same surface (collapse: best_view)
  uint64_t collapsed = 0;         // dropped: covered by the view their cluster chose
  uint64_t kept_uncovered = 0;    // their cluster chose another view, which does not emit them: not collapsed
  // Of the pixels neither collapsed nor redundant (their own tests are judged last, core/point_verdicts.h):
  uint64_t free_space = 0;        // dropped: views observed its place as empty
  uint64_t outliers = 0;          // dropped: too few consistent views
  uint64_t emitted = 0;
  uint64_t interpolated = 0;      // of the emitted: combined from the anchors around them (core/combine_anchors.h)
  uint64_t not_owned = 0;         // valid pixels the owner rejected (another tile's), not counted above
  CollapseStats& operator+=(const CollapseStats& o) {
    input_pixels += o.input_pixels;
    collapsed += o.collapsed;
    kept_uncovered += o.kept_uncovered;
    redundant += o.redundant;
    free_space += o.free_space;
    outliers += o.outliers;
    emitted += o.emitted;
    interpolated += o.interpolated;
    not_owned += o.not_owned;
    return *this;
  }
};

// Emits the fused points of view `v` to `sink` in row order (deterministic for any thread count).
// `redundancy_judges`: the views searched for a better view (core/redundancy.h, RedundancySearchOrder);
// `combine_views` (fusion.combine: average) refine the emitted depths (both per pixel, core/consulted_views.h),
// weighted with the views'
// `noise_factor` (core/view_noise.h; empty = equal). Pixels whose own point `owner` does not own are skipped and
// not counted (core/owned_region.h; patches wholly inside or outside it are decided at once). The points take
// their colours from `colours` (view v's, as SacView::image; null = grey).
CollapseStats EmitView(uint32_t v, const std::vector<SacView>& views, const NodeTable& nodes,
                       const NodeLabels& chosen_view, const ConsultedViews& redundancy_judges,
                       const ConsultedViews& combine_views,
                       const std::vector<double>& noise_factor, const PointVerdicts& verdicts,
                       const SacOptions& options, const OwnedRegion& owner, const RgbImage* colours,
                       PointSink& sink);

}  // namespace sacfuse
