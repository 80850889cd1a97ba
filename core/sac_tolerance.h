#pragma once
// Depth agreement tolerance, shared by correspondences, collapse and the outlier test so that "consistent" means
// one thing everywhere: |z_a - z_b| <= depth_tolerance_gsd * GSD(z) + depth_tolerance_rel * z.
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

inline double DepthToleranceM(const SacView& view, double depth_m, const SacOptions& options) {
  return options.depth_tolerance_gsd * view.GsdAt(depth_m) + options.depth_tolerance_rel * depth_m;
}

// Whether the depth map of `view` agrees with the looked-up point within `tolerance_gsd` local GSDs (no relative
// part): the strict test of the quality unary.
inline bool DepthAgreesStrictly(const SacView& view, const DepthLookup& lookup, double tolerance_gsd) {
  return lookup.inside && IsValidDepth(lookup.stored_depth_m) &&
         std::abs(lookup.stored_depth_m - lookup.z_m) <= tolerance_gsd * view.GsdAt(lookup.z_m);
}

// Whether the depth map of `view` holds a surface at `lookup` agreeing with the looked-up point.
inline bool DepthAgrees(const SacView& view, const DepthLookup& lookup, const SacOptions& options) {
  return lookup.inside && IsValidDepth(lookup.stored_depth_m) &&
         std::abs(lookup.stored_depth_m - lookup.z_m) <= DepthToleranceM(view, lookup.z_m, options);
}

}  // namespace sacfuse
