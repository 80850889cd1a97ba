#pragma once
// Options of Select-and-Combine fusion (YAML section `fusion`). Defaults were chosen by measured F1 on simulated
// blocks with errors (see docs/design.md); units in each comment.
#include <string>

#include "core/superpixels.h"

namespace sacfuse {

// Default of SacOptions::combine_slope_step_sigmas, also the default of the structs that take it over
// (DepthCombineOptions, ViewNoiseOptions), so a test with default options runs what `sacfuse run` runs.
inline constexpr double kCombineSlopeStepSigmas = 3.0;
// The default of SacOptions::combine_later_pass_min_shift_gsd (and of DepthCombineOptions'), local GSDs.
inline constexpr double kCombineLaterPassMinShiftGsd = 1.0;

struct SacOptions {
  // --- Neighbour views, chosen from geometry (not a fixed list).
  int max_neighbor_views = 10;          // per view, the best by footprint overlap x cos(view angle)
  double max_view_angle_deg = 65.0;     // max angle between two views' viewing directions, degrees
  double min_footprint_overlap = 0.05;  // min fraction of a view's footprint box shared with the neighbour
  // --- Correspondences (point groups), paper Section III.B / IV.D.
  //   reprojection: project a node into each neighbour view, take the superpixel there if its depth agrees.
  //   proximity:    3D radius search among all nodes (k-d tree); the nearest node of each other view.
  //   dense:        the input's dense-matching consistency (COLMAP consistency graphs) names the views; the
  //                 node is projected into them without a depth test.
  std::string correspondence = "reprojection";
  // "Same surface" tolerance for correspondences, collapse coverage and the outlier test, in units of the local
  // GSD (depth / focal), plus a fraction of the depth (COLMAP's 1 % would be 0.01).
  double depth_tolerance_gsd = 3.0;
  double depth_tolerance_rel = 0.0;
  // Reprojection correspondences: with estimated noise (combine: average), depths also agree within this many
  // sigmas of the two views' depth difference (0 = the tolerance above only).
  double correspondence_tolerance_sigmas = 1.0;
  double proximity_radius_m = 0.0;      // proximity strategy search radius, metres; 0 = 1.5 x superpixel size
  // --- Netlets (Algorithm 1): nodes are superpixel centroids; edges join nodes closer than tau.
  double tau_m = 2.0;                   // edge threshold, metres (paper: 2 m); weight = exp(-distance)
  //   node:      one Netlet per node (the node and its correspondents), as Algorithm 1; each Netlet decides its
  //              centre's label only (Netlets overlap).
  //   partition: disjoint Netlets (greedy seeds; see netlets.h); each Netlet decides all its members.
  std::string netlets = "node";
  // --- Labelling: Eq. (2) per Netlet, solved exactly (branch and bound) or within 2x (alpha-expansion).
  //   paper:   constant unary (= 1); ties go to the lowest view index (the paper leaves them to chance).
  //   quality: expected depth uncertainty of the candidate view (its local GSD), how many other views agree
  //            with it, and how far the node would move.
  std::string unary = "quality";
  double quality_weight = 1.0;          // weight of (sigma / best sigma - 1), sigma ~ depth^2 / (focal cos incidence)
  double min_incidence_cos = 0.2;       // floor of cos(incidence) in that sigma (grazing views: 5x penalty at most)
  double agreement_weight = 1.0;        // weight of (1 - fraction of the other views agreeing)
  double agreement_tolerance_gsd = 1.5;  // stricter tolerance for "agreeing" in the quality unary, local GSDs
  double displacement_weight = 0.5;     // weight of min(|p_node - p_label| / tau, 1)
  double smoothness_weight = 0.0;       // bonus for the label of adjacent clusters of the same view (0 = off)
  int smoothness_rounds = 2;            // Jacobi rounds of that cross-Netlet smoothness
  // --- Collapse and outliers.
  // Coverage (collapse, step 6): with estimated noise (combine: average), the chosen view "emits the surface" also
  // when the depths differ by less than this many sigmas of their difference (0 = the tolerance above only).
  double coverage_tolerance_sigmas = 5.0;
  // Collapse (core/collapse.h, core/redundancy.h):
  //   netlet:    a pixel is dropped when the view its Netlet chose emits that surface (the coverage rule).
  //   best_view: also when a more precise view (lower estimated depth noise there) holds and emits the same surface,
  //              so each surface patch comes from one depth map.
  //   none:      nothing is dropped for another view: every view's pixels that pass their own point tests are
  //              emitted (each averaged when combine: average). For depth maps from a stereo matcher, whose errors
  //              one patch's single view does not average out (docs/design.md, "Collapse").
  std::string collapse = "best_view";
  double redundancy_tolerance_sigmas = 3.0;  // best_view: "same surface" also within this many sigmas of the
                                             // estimated noise of the two depths' difference (0 = strict tolerance)
  // Free space (core/point_verdicts.h): a point is dropped when at least free_space_min_views (0 = off) of the combine
  // views see through it by more than the tolerance and free_space_sigmas sigma of the estimated noise.
  int free_space_min_views = 2;
  double free_space_sigmas = 3.0;
  // A point that none of the first free_space_early_pass_views judges (the consulted views, those that see its
  // region best first) sees through passes without asking the rest (0 = always every judge). Issue 13: with 16,
  // Dortmund tile 6_6 -11 % CPU, aerial-bench F1 within -0.0001 / +0.0003 (docs/design.md).
  int free_space_early_pass_views = 16;
  // A view sees through a point only where every valid depth within this many pixels of the point's projection
  // does (0 = the pixel alone): one pixel of registration error then does not make the pixels next to an edge of
  // that view free space (aerial-bench St Barth: roof edges). Except for points within free_space_edge_band_px
  // pixels of a foreground edge of their own view (a jump of more than depth_edge_jump_gsd local GSDs, see
  // core/depth_edge.h), where matchers fatten the foreground: those are judged by the pixel alone.
  int free_space_window_px = 1;
  int free_space_edge_band_px = 2;
  double depth_edge_jump_gsd = 8.0;
  int min_consistent_views = 4;         // a point must agree with this many views (its own included), fewer
                                        // where fewer can observe it (see collapse.h)
  double outlier_expected_factor = 1.5; // with estimated noise: at most 1 + this x the expected agreeing views
                                        // (0 = off)
  // Weak support (core/point_verdicts.h): where a neighbour that could observe a point has no depth there (an
  // invalid pixel with no valid depth in front of the point within kDepthEdgeReachPx pixels, so not an occlusion),
  // the point must agree with this many depth maps (its own included), at most min_consistent_views and 1 + the
  // views that could observe it (0 = off). A raw stereo depth and its partner view's depth come from the same match
  // and share its errors, so one confirming view is not enough where others found nothing. Off by default: 3 took
  // Brighton Beach's raw-map floaters from 0.376 % to 0.133 % but cost completeness on filtered maps and on a
  // simulated raw SGBM block (docs/design.md).
  int weak_support_min_views = 0;
  // With weak support on: a pixel within weak_support_rim_px pixels of a hole of its own depth map (the rim of what
  // the matcher matched, where single-pair stereo depths stray most) needs weak_support_min_views agreeing depth maps
  // (at most min_consistent_views) also where fewer views could observe it (0 = no rim rule). 2 took Brighton Beach's
  // raw-map floaters in the held-out view by the forest edge from 0.162 % to 0.121 % (docs/design.md).
  int weak_support_rim_px = 2;
  // Independent support (core/point_verdicts.h): where the input names each view's matching partners (the views
  // its depth map was matched with in stereo pairs; COLMAP's stereo/patch-match.cfg), the views that are not its
  // partners and agree with a point must be at least as many as those that could observe it but have no depth
  // there. Off by default: with weak support 3 it took Brighton Beach's raw-map held-out floaters from 0.118 % to
  // 0.094 % (coverage 0.98 -> 0.97) but cost 4 F1 points on a simulated raw SGBM block (docs/design.md).
  bool independent_support = false;
  //   select:  an emitted pixel keeps its selected view's depth (the paper's collapse, no averaging).
  //   average: it keeps the selected view's pixel (same point count) with its depth along that ray averaged
  //            over the agreeing depth maps (core/depth_combine.h).
  std::string combine = "average";
  double combine_gate_gsd = 4.0;        // average: depth maps within this many local GSDs along the ray take part,
  double combine_gate_sigmas = 3.0;     // or within this many sigmas of the estimated noise of the own depth
  // average: the ray-surface slope is taken over max(1 GSD, this many sigmas of the own depth's estimated noise)
  // along the ray (0 = 1 GSD); also the step of the noise estimate's second pass (core/view_noise.h)
  double combine_slope_step_sigmas = kCombineSlopeStepSigmas;
  // average: how the agreeing depth maps are weighted (core/depth_combine.h): "view" (1 / k_v^2, the per-view noise
  // factor estimated from the data, so an inconsistent depth map counts less), "equal", or "noise" (the full
  // stereo model: 1 / (k_v z^2 / f)^2 times the ray intersection's slope squared).
  std::string combine_weights = "view";
  // average: where a neighbour's surface meets the ray (core/depth_combine.h): "plane" (along the plane fitted to
  // the pixel's superpixel, for neighbours within 30 deg of the ray where the ray does not graze the plane; else
  // the secant) or "secant" (one secant step on the neighbour's depth map, its slope from two samples).
  std::string combine_surface = "plane";
  // average: passes of the mean; each after the first finds the neighbours' surfaces again from the previous mean
  // (closer to the surface than the own depth, so the plane and the secant extrapolate less).
  int combine_passes = 2;
  // average: the passes after the first take a neighbour's surface within this fraction of the gate around the
  // previous mean (and within the whole gate of the own depth). 1 (the default) = the whole gate; 0.75 gains on
  // aerial-bench and loses on our bench (core/depth_combine.h).
  double combine_later_pass_gate = 1.0;
  // average: a later pass only where the previous one moved the ray's centre by at least this many local GSDs
  // (0 = every pass always; core/depth_combine.h). >= 0
  double combine_later_pass_min_shift_gsd = kCombineLaterPassMinShiftGsd;
  // average: combine exactly only the anchors of each patch (every second row and column) and interpolate the
  // other depth maps' mean surface for the emitted pixels between them where it is smooth (core/combine_anchors.h);
  // false = every emitted pixel exactly.
  bool combine_anchors = true;
  // average: views consulted per view and region (core/consulted_views.h): the combine, the free-space judges, the
  // better-view search and the noise estimate.
  int combine_max_views = 40;
  double combine_max_view_angle_deg = 65.0;  // average: max angle between their viewing directions, degrees
  double combine_region_m = 128.0;      // average: side of the square regions they are chosen for, metres
                                        // (0 = one list per view)
  // --- Superpixels (nodes).
  SuperpixelOptions superpixels;
};

// Throws ConfigError naming `SacOptions.<field>`, the value and the rule for every invalid field, then for the
// superpixel options. An invariant of RunSacFusion: the YAML keys are checked by config/option_table.cc.
void ValidateSacOptions(const SacOptions& options);

}  // namespace sacfuse
