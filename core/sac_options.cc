#include "core/sac_options.h"

#include "core/depth_edge.h"
#include "core/option_check.h"

namespace sacfuse {

void ValidateSacOptions(const SacOptions& o) {
  OptionChecker c;
  c.InRange("SacOptions.max_neighbor_views", o.max_neighbor_views, 1, 64);
  c.InRange("SacOptions.max_view_angle_deg", o.max_view_angle_deg, 0.0, 180.0);
  c.InRange("SacOptions.min_footprint_overlap", o.min_footprint_overlap, 0.0, 1.0);
  c.OneOf("SacOptions.correspondence", o.correspondence, {"reprojection", "proximity", "dense"});
  c.Greater("SacOptions.depth_tolerance_gsd", o.depth_tolerance_gsd, 0.0);
  c.InRange("SacOptions.depth_tolerance_rel", o.depth_tolerance_rel, 0.0, 0.5);
  c.AtLeast("SacOptions.proximity_radius_m", o.proximity_radius_m, 0.0);
  c.Greater("SacOptions.tau_m", o.tau_m, 0.0);
  c.OneOf("SacOptions.netlets", o.netlets, {"node", "partition"});
  c.OneOf("SacOptions.unary", o.unary, {"paper", "quality"});
  c.AtLeast("SacOptions.quality_weight", o.quality_weight, 0.0);
  c.InRange("SacOptions.min_incidence_cos", o.min_incidence_cos, 0.01, 1.0);
  c.AtLeast("SacOptions.agreement_weight", o.agreement_weight, 0.0);
  c.Greater("SacOptions.agreement_tolerance_gsd", o.agreement_tolerance_gsd, 0.0);
  c.AtLeast("SacOptions.displacement_weight", o.displacement_weight, 0.0);
  c.AtLeast("SacOptions.smoothness_weight", o.smoothness_weight, 0.0);
  c.InRange("SacOptions.smoothness_rounds", o.smoothness_rounds, 0, 20);
  c.OneOf("SacOptions.collapse", o.collapse, {"netlet", "best_view", "none"});
  c.AtLeast("SacOptions.redundancy_tolerance_sigmas", o.redundancy_tolerance_sigmas, 0.0);
  c.InRange("SacOptions.free_space_min_views", o.free_space_min_views, 0, 64);
  c.AtLeast("SacOptions.free_space_sigmas", o.free_space_sigmas, 0.0);
  c.InRange("SacOptions.free_space_early_pass_views", o.free_space_early_pass_views, 0, 64);
  c.InRange("SacOptions.free_space_window_px", o.free_space_window_px, 0, 8);
  c.InRange("SacOptions.free_space_edge_band_px", o.free_space_edge_band_px, 0, kDepthEdgeReachPx);
  c.Greater("SacOptions.depth_edge_jump_gsd", o.depth_edge_jump_gsd, 0.0);
  c.InRange("SacOptions.min_consistent_views", o.min_consistent_views, 1, 64);
  c.AtLeast("SacOptions.correspondence_tolerance_sigmas", o.correspondence_tolerance_sigmas, 0.0);
  c.AtLeast("SacOptions.outlier_expected_factor", o.outlier_expected_factor, 0.0);
  c.InRange("SacOptions.weak_support_min_views", o.weak_support_min_views, 0, 64);
  c.InRange("SacOptions.weak_support_rim_px", o.weak_support_rim_px, 0, kDepthEdgeReachPx);
  c.AtLeast("SacOptions.coverage_tolerance_sigmas", o.coverage_tolerance_sigmas, 0.0);
  c.OneOf("SacOptions.combine", o.combine, {"select", "average"});
  c.Greater("SacOptions.combine_gate_gsd", o.combine_gate_gsd, 0.0);
  c.AtLeast("SacOptions.combine_gate_sigmas", o.combine_gate_sigmas, 0.0);
  c.AtLeast("SacOptions.combine_slope_step_sigmas", o.combine_slope_step_sigmas, 0.0);
  c.OneOf("SacOptions.combine_weights", o.combine_weights, {"view", "equal", "noise"});
  c.OneOf("SacOptions.combine_surface", o.combine_surface, {"plane", "secant"});
  c.InRange("SacOptions.combine_passes", o.combine_passes, 1, 4);
  c.InRange("SacOptions.combine_later_pass_gate", o.combine_later_pass_gate, 0.05, 1.0);
  c.AtLeast("SacOptions.combine_later_pass_min_shift_gsd", o.combine_later_pass_min_shift_gsd, 0.0);
  c.InRange("SacOptions.combine_max_views", o.combine_max_views, 1, 64);
  c.InRange("SacOptions.combine_max_view_angle_deg", o.combine_max_view_angle_deg, 0.0, 180.0);
  c.InRange("SacOptions.combine_region_m", o.combine_region_m, 0.0, 1e6);
  c.ThrowIfFailed("SAC options");
  ValidateSuperpixelOptions(o.superpixels);
}

}  // namespace sacfuse
