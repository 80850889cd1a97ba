#pragma once
// `fusion.method: disparity_normal` — consistency in disparity and normal space with averaging, as the SAC paper
// describes its reference [13] (Galliani et al. 2015, Gipuma's `fusibile`).
//
// Views are visited in the plan's order (jobs: most precise first). For each valid pixel p of the current
// (reference) view i that no earlier fused point has used, with point X and normal n_p, X is projected into each
// neighbour view j; at the pixel q it falls on (nearest) with j's depth d_q and normal n_q, j is CONSISTENT when
//   |f_i b_ij / z - f_i b_ij / d_q| <= disparity_threshold_px   (z = depth of X in j; f_i = i's focal length in
//        depth-raster pixels, b_ij = |C_i - C_j| the baseline: the disparity difference fusibile tests), and
//   angle(n_p, n_q) <= normal_threshold_deg.
// With at least min_consistent_views consistent neighbours (the reference not counted, as fusibile) the point is
// emitted as the plain MEAN of X and the consistent neighbours' points (each q back-projected with d_q), with
// the mean colour of those pixels; its source view (LAS point source ID) is the reference view i. The pixels q
// are marked used, so they seed no point of their own later (they may still be averaged into other points, as in
// fusibile). Otherwise p is dropped.
// Normals: the input's normal maps are NOT read; every view's normals are computed from its depth by a local
// plane fit (core/depth_normals.h, window 2 r + 1), in core, so every input format behaves alike.
#include "core/fusion_stats.h"
#include "core/method_views.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

struct DisparityNormalOptions {
  double disparity_threshold_px = 0.5;  // disparity difference, pixels (fusibile's default disp_thresh). > 0
  double normal_threshold_deg = 30.0;   // max angle between normals, degrees (paper, fusibile). (0, 180]
  int min_consistent_views = 2;         // consistent neighbour views needed (paper: two; fusibile's default). >= 1
  int normal_radius_px = 2;             // plane-fit window radius for the computed normals, pixels. [1, 10]
};

// Throws ConfigError naming DisparityNormalOptions.<field> for every invalid field (an invariant of the run; the
// YAML keys are checked by config/option_table.cc).
void ValidateDisparityNormalOptions(const DisparityNormalOptions& options);

// `plan` null = ViewPlanFromDepth(views, NeighborViewOptions{}). Superpixels are not used (may be null).
// Counters: inconsistent (dropped: too few consistent views), members_averaged (neighbour points averaged in),
// skipped_marked (pixels used by an earlier point).
FusionStats RunDisparityNormalFusion(const std::vector<SacView>& views, const DisparityNormalOptions& options,
                                     PointSink& sink, const ViewPlan* plan = nullptr);

}  // namespace sacfuse
