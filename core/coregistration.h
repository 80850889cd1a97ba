#pragma once
// Per-view co-registration of a block's depth maps (issue 12), before fusion. The written poses of an aerial block
// carry small errors (bundle adjustment residuals, boresight and timing errors): each view's depth map lands a little
// rotated and shifted against its neighbours', and no fusion rule can make two surfaces one where they disagree by
// more than their noise. Here every view gets a small rigid correction that brings its surface onto its neighbours'.
//
// The problem: view k's points move as X' = X + w_k x (X - P_k) + t_k (a rotation w_k about P_k, the centroid of
// the view's samples, and a translation t_k). Every sample of view a is projected into each neighbour b; the
// residual is the distance from b's surface point there along b's surface normal (point to plane). Residuals over
// max_residual_gsd local GSDs are left out, the rest weighed by Huber (huber_gsd). A weak prior keeps each
// correction small where the data say nothing (rotations measured by the footprint's rms radius), and the mean
// correction over all views is held at zero, so the block's datum (its georeference) does not move. Damped
// Gauss-Newton (Levenberg-Marquardt with the diagonal doubled): the rotation and translation of a narrow-angle view
// are hardly separated by the data, and undamped steps let them drift together. Each iteration projects again with
// the corrected poses. Measured, and how the defaults were chosen: docs/design.md (2,000 samples, 12 neighbours
// and 20 steps gain as much as 20,000, 24 and 8 at a sixth of the time).
//
// The pivot is the footprint centroid, not the camera centre: rotations about the camera gained more on some
// aerial-bench blocks but lost on our narrow 11-degree city block, where a rotation about the camera is mostly a
// shift of the footprint and the two drift together.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/raster.h"
#include "core/rigid3.h"
#include "core/view.h"

namespace sacfuse {

struct CoregistrationOptions {
  bool enabled = true;            // correct every view's pose against its neighbours' depth maps before fusion
  // Depth maps are read once and decimated (every k-th pixel, k odd) to at most this many pixels per view.
  int max_pixels_per_view = 250000;
  int samples_per_view = 2000;    // samples of each view projected into its neighbours (a regular grid), at most
  int iterations = 20;            // damped Gauss-Newton steps, each projecting again; 1-50
  int max_neighbor_views = 12;    // views each view is compared with (footprint overlap x cos angle, best first)
  double max_view_angle_deg = 65.0;  // views whose viewing directions differ by more are not compared, degrees
  double huber_gsd = 1.2;         // Huber threshold of the point-to-plane residual, local GSDs (depth / focal)
  double max_residual_gsd = 8.0;  // residuals larger than this are left out, local GSDs
};

// Throws ConfigError naming the key (coregistration.<field>), the value and the rule.
void ValidateCoregistrationOptions(const CoregistrationOptions& options);

// Decimation factor for a raster of width x height: the smallest odd k with (width / k) * (height / k) at most
// max_pixels (k >= 1).
int CoregistrationDecimation(int width, int height, int max_pixels);
// Every k-th pixel of `depth` (k odd): pixel (r, c) of the result is pixel (k r + (k-1)/2, k c + (k-1)/2), whose
// centre is k times the result pixel's centre, so the result's camera is the depth raster's scaled by 1/k exactly.
DepthMap DecimateDepth(const DepthMap& depth, int k);
// The rows of a raster `height` rows high that DecimateDepth keeps: k r + (k-1)/2 for r < height / k. A reader
// that can read rows alone reads only these (DepthBlock::ReadDepthRows), 1 / k of the map.
std::vector<int> DecimatedRows(int height, int k);
// DecimateDepth of a raster of which `rows` holds only the rows DecimatedRows(height, k), in that order.
DepthMap DecimateDepthRows(const DepthMap& rows, int k);

// One view as co-registration sees it.
struct CoregistrationInput {
  View view;                    // intrinsics at image resolution (for the GSD), pose as given
  PinholeCamera depth_camera;   // the camera of `depth` (the decimated raster)
  DepthMap depth;               // decimated z-depth, metres
};

// What happened to one view.
struct ViewCorrection {
  Rigid3d cam_from_world;        // the corrected pose
  double rotation_deg = 0.0;     // angle of the correction's rotation
  Eigen::Vector3d shift_m = Eigen::Vector3d::Zero();  // how far the centroid of the view's samples moved (world)
  size_t samples = 0;            // valid decimated pixels
  size_t residuals_before = 0, residuals_after = 0;   // residuals with the view on either side, first / last pass
  double rms_before_m = 0.0, rms_after_m = 0.0;       // their rms (within the window), metres
};

struct CoregistrationIteration {
  size_t residuals = 0;
  double weighted_rms_m = 0.0;       // sqrt(sum w r^2 / n) with the Huber weights
  double median_step_deg = 0.0;      // median over views of this step's rotation
  double median_step_m = 0.0;        // median over views of this step's translation
};

// Over the views: medians (and maxima) of the corrections and of the residual rms.
struct CoregistrationSummary {
  double median_rotation_deg = 0.0, max_rotation_deg = 0.0;
  double median_shift_m = 0.0, max_shift_m = 0.0;
  double median_rms_before_m = 0.0, median_rms_after_m = 0.0;
};

struct CoregistrationResult {
  CoregistrationSummary summary;
  std::vector<ViewCorrection> views;  // by view index
  std::vector<CoregistrationIteration> iterations;  // the last entry: residuals after the final step
  size_t pairs = 0;                   // compared view pairs (a, b) of the first pass
};

// Corrected poses of `inputs` (indexed like the block's views). Parallel over views, deterministic for any thread
// count. Views without samples, or without neighbours, keep their poses (apart from the datum's share).
CoregistrationResult Coregister(const std::vector<CoregistrationInput>& inputs, const CoregistrationOptions& options);

}  // namespace sacfuse
