#pragma once
// `fusion.method: consistency` — depth-map merging by geometric consistency as the SAC paper describes its
// reference [15] (Shen 2013, Fig. 4): every depth map is reprojected into its neighbours, and depths there that
// it occludes or that repeat it are removed.
//
// Views are visited in the plan's order (jobs: most precise first, by z^2/f). For each remaining (not yet removed)
// valid pixel p of the current view i, its point X is emitted (colour and source view from i), and X is projected
// into each neighbour view j that comes LATER in the order; at the pixel q it falls on (nearest, the pixel that
// contains the projection), with z the depth of X in j and d = j's depth at q:
//   |z - d| / d <= depth_threshold_rel  -> q is redundant (it repeats X): removed;
//   z < d (1 - depth_threshold_rel)      -> q is occluded by X (X lies in front of j's surface): removed.
// Removed pixels are never emitted nor projected. So where several views agree, the point of the FIRST view in
// the order survives — the view with the smallest expected depth error, which is why the jobs order views by
// precision (core/method_views.h) — and the later views only add what it did not see. Neighbours earlier in
// the order are not touched (they have emitted already). No minimum number of agreeing views: a pixel no
// earlier view removed is kept even if no other view sees it (as [15]).
#include "core/fusion_stats.h"
#include "core/method_views.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

struct ConsistencyOptions {
  // Relative depth threshold of the redundancy and occlusion tests, fraction of the neighbour's depth
  // (paper: 1 %). (0, 0.5].
  double depth_threshold_rel = 0.01;
};

// Throws ConfigError naming ConsistencyOptions.<field> for every invalid field (an invariant of the run; the YAML
// keys are checked by config/option_table.cc).
void ValidateConsistencyOptions(const ConsistencyOptions& options);

// `plan` null = ViewPlanFromDepth(views, NeighborViewOptions{}). Superpixels are not used (may be null).
// Counters: redundant_hits, occluded_hits (projections that removed a neighbour's depth; a depth may be hit more
// than once), skipped_marked (valid pixels skipped because an earlier view removed them).
FusionStats RunConsistencyFusion(const std::vector<SacView>& views, const ConsistencyOptions& options,
                                 PointSink& sink, const ViewPlan* plan = nullptr);

}  // namespace sacfuse
