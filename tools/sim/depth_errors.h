#pragma once
// Seeded error models turning a view's TRUE depth map and pose into realistic MVS output. Each model is switchable
// (magnitude 0 = off); `errors.enabled = false` switches them all off. Magnitudes are nadir values times
// `errors.scale`; obliques get `oblique_factor` times the stereo noise, bias amplitude and blunder rate.
//
//  Pose:        written centre C' = C + dC, dC ~ N(0, pose_position_sigma_m^2 I);
//               written rotation R'_wc = R_wc * Exp(dtheta), dtheta ~ N(0, pose_rotation_sigma^2 I) (camera frame).
//               The depth map is rendered with the true pose, so back-projecting it with the written pose moves
//               every point by the rigid transform T'_wc * T_cw.
//  Edges:       foreground edge pixels E = valid pixels with a 4-neighbour more than fattening_min_step_m behind.
//  Fattening:   d(p) <- m_r(p) = min of d over E within a disc of r = fattening_px pixels, where d(p) - m_r(p) >
//               fattening_min_step_m (the foreground spreads r pixels over the background at depth edges).
//  Occlusion:   pixels (not fattened) where d(p) - min of d over E on a segment of +-(r + occlusion_strip_px)
//               pixels along the image axis of the flight direction (the stereo baseline) > fattening_min_step_m
//               become invalid (a left-right check fails in the strip the partner image cannot see).
//  Stereo:      d <- d + sigma_z(d) n(p), sigma_z = d^2 sigma_disparity / (f B) (f image focal, pixels; B
//               stereo_baseline_m or the along-track baseline); n = unit Gaussian field correlated over
//               noise_correlation_px pixels (see CorrelatedGaussianField).
//  Bias:        d <- d + A b(u, v), |b| <= 1 a sum of 3 cosine modes of <= 1.2 cycles per image (random
//               frequency, phase, weight), A = bias_amplitude_m.
//  Blunders:    Poisson(blunders_per_mpx x depth megapixels) discs, radius ~ U(0.5, 1.5) x blunder_radius_px,
//               centre uniform; every valid pixel in a disc gets the blob's offset s sigma_b (0.5 + |N(0, 1)|),
//               s = +-1 (expected covered fraction 1 - exp(-rate 1e-6 pi E[r^2]), E[r^2] = 13/12 r_mean^2).
//  Dropouts:    a unit Gaussian field correlated over 1.5 pixels, thresholded at InverseNormalCdf(1 - fraction):
//               that fraction of pixels, in small clusters, becomes invalid.
// Pixel sizes are IMAGE pixels in the options and are divided by depth_downsample here.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/raster.h"
#include "core/rigid3.h"
#include "tools/sim/error_fields.h"
#include "tools/sim/sim_options.h"

namespace sacfuse::sim {

// Effective magnitudes for one view (depth-raster pixels unless stated).
struct ViewErrorModel {
  bool enabled = false;
  double disparity_sigma_px = 0.0;   // image pixels
  double focal_px = 1.0;             // image focal length, pixels
  double baseline_m = 1.0;
  double noise_correlation_px = 0.0;
  double bias_amplitude_m = 0.0;
  int fattening_px = 0;
  double fattening_min_step_m = 1.0;
  double blunders_per_mpx = 0.0;     // per million depth pixels
  double blunder_radius_px = 0.0;
  double blunder_depth_sigma_m = 0.0;
  int occlusion_strip_px = 0;
  bool baseline_along_columns = true;  // flight direction runs along image columns (u) rather than rows (v)
  double dropout_fraction = 0.0;

  // sigma_z at depth d, metres.
  double StereoSigma(double depth) const { return depth * depth * disparity_sigma_px / (focal_px * baseline_m); }
};

ViewErrorModel MakeViewErrorModel(const SimErrorOptions& options, bool oblique, double focal_px, double baseline_m,
                                  int depth_downsample, bool baseline_along_columns);

struct DepthErrorReport {
  std::vector<CosineMode> bias_modes;
  int blunder_count = 0;
  size_t blunder_pixels = 0;
  size_t fattened_pixels = 0;
  size_t occluded_pixels = 0;
  size_t dropout_pixels = 0;
  size_t valid_in = 0;   // valid pixels of the true depth map
  size_t valid_out = 0;  // valid pixels written
};

// The erroneous depth map; `key` seeds every random draw (same key -> same output).
DepthMap ApplyDepthErrors(const DepthMap& true_depth, const ViewErrorModel& model, uint64_t key,
                          DepthErrorReport* report);

struct PoseError {
  Eigen::Vector3d center_delta_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_delta_rad = Eigen::Vector3d::Zero();  // rotation vector in the camera frame
};
PoseError DrawPoseError(const SimErrorOptions& options, uint64_t key);
// The written (erroneous) cam_from_world.
Rigid3d ApplyPoseError(const Rigid3d& true_cam_from_world, const PoseError& error);

}  // namespace sacfuse::sim
