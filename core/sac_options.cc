#include "core/sac_options.h"

#include "core/option_check.h"

namespace sacfuse {

void ValidateSacOptions(const SacOptions& o) {
  OptionChecker c;
  c.InRange("fusion.max_neighbor_views", o.max_neighbor_views, 1, 64);
  c.InRange("fusion.max_view_angle_deg", o.max_view_angle_deg, 0.0, 180.0);
  c.InRange("fusion.min_footprint_overlap", o.min_footprint_overlap, 0.0, 1.0);
  c.OneOf("fusion.correspondence", o.correspondence, {"reprojection", "proximity", "dense"});
  c.Greater("fusion.depth_tolerance_gsd", o.depth_tolerance_gsd, 0.0);
  c.InRange("fusion.depth_tolerance_rel", o.depth_tolerance_rel, 0.0, 0.5);
  c.AtLeast("fusion.proximity_radius_m", o.proximity_radius_m, 0.0);
  c.Greater("fusion.tau_m", o.tau_m, 0.0);
  c.OneOf("fusion.netlets", o.netlets, {"node", "partition"});
  c.OneOf("fusion.unary", o.unary, {"paper", "quality"});
  c.AtLeast("fusion.quality_weight", o.quality_weight, 0.0);
  c.InRange("fusion.min_incidence_cos", o.min_incidence_cos, 0.01, 1.0);
  c.AtLeast("fusion.agreement_weight", o.agreement_weight, 0.0);
  c.Greater("fusion.agreement_tolerance_gsd", o.agreement_tolerance_gsd, 0.0);
  c.AtLeast("fusion.displacement_weight", o.displacement_weight, 0.0);
  c.AtLeast("fusion.smoothness_weight", o.smoothness_weight, 0.0);
  c.InRange("fusion.smoothness_rounds", o.smoothness_rounds, 0, 20);
  c.OneOf("fusion.collapse", o.collapse, {"netlet", "best_view"});
  c.AtLeast("fusion.redundancy_tolerance_sigmas", o.redundancy_tolerance_sigmas, 0.0);
  c.InRange("fusion.free_space_min_views", o.free_space_min_views, 0, 64);
  c.AtLeast("fusion.free_space_sigmas", o.free_space_sigmas, 0.0);
  c.InRange("fusion.min_consistent_views", o.min_consistent_views, 1, 64);
  c.AtLeast("fusion.correspondence_tolerance_sigmas", o.correspondence_tolerance_sigmas, 0.0);
  c.AtLeast("fusion.outlier_expected_factor", o.outlier_expected_factor, 0.0);
  c.AtLeast("fusion.coverage_tolerance_sigmas", o.coverage_tolerance_sigmas, 0.0);
  c.OneOf("fusion.combine", o.combine, {"select", "average"});
  c.Greater("fusion.combine_gate_gsd", o.combine_gate_gsd, 0.0);
  c.AtLeast("fusion.combine_gate_sigmas", o.combine_gate_sigmas, 0.0);
  c.InRange("fusion.combine_max_views", o.combine_max_views, 1, 64);
  c.InRange("fusion.combine_max_view_angle_deg", o.combine_max_view_angle_deg, 0.0, 180.0);
  c.Absorb([&] { ValidateSuperpixelOptions(o.superpixels); });
  c.ThrowIfFailed("fusion options");
}

}  // namespace sacfuse
