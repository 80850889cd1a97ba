#pragma once
// Depth agreement tolerance, shared by correspondences, collapse and the outlier test so that "consistent" means
// one thing everywhere: |z_a - z_b| <= depth_tolerance_gsd * GSD(z) + depth_tolerance_rel * z; and, with the
// per-view noise factors of core/view_noise.h, the noise-aware variants.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

// Relative z-error scale of a depth map at depth z: z * gsd(z) = z^2 / focal (stereo: sigma_z = z^2 sigma_d / (f B)),
// up to the view's noise factor k.
inline double DepthNoiseScale(const SacView& view, double z_m) { return z_m * view.GsdAt(z_m); }

// The step along a ray between the two samples of the combine's secant (core/depth_combine.h), metres: one local
// GSD, or slope_step_sigmas sigma of the depth's estimated noise where that is longer.
inline double SecantStepM(double gsd_m, double sigma_m, double slope_step_sigmas) {
  return std::max(gsd_m, slope_step_sigmas * sigma_m);
}

// Estimated z-noise of view i at depth z, metres: k_i z^2 / f (noise_factor from EstimateViewNoiseFactors).
inline double DepthSigmaM(const std::vector<SacView>& views, const std::vector<double>& noise_factor, uint32_t i,
                          double z_m) {
  return noise_factor[i] * DepthNoiseScale(views[i], z_m);
}

// Sigma of the difference of two independent depths (std::hypot's overflow guard is not needed for metres and cost
// 9 % of SAC's time).
inline double PairSigmaM(double sigma_a_m, double sigma_b_m) {
  return std::sqrt(sigma_a_m * sigma_a_m + sigma_b_m * sigma_b_m);
}

// Whether two depths differing by `difference_m` agree within `sigmas` sigma of their difference.
inline bool AgreeWithinSigmas(double difference_m, double sigma_a_m, double sigma_b_m, double sigmas) {
  return std::abs(difference_m) <= sigmas * PairSigmaM(sigma_a_m, sigma_b_m);
}

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
