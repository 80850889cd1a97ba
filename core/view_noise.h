#pragma once
// Per-view depth noise factors k for SAC's averaging combine (core/depth_combine.h), estimated from the depth
// maps themselves: the model is sigma_v(z) = k_v * z * gsd_v(z), where z * gsd(z) = z^2 / focal is the stereo
// growth of depth error with distance and k_v holds what geometry cannot tell (baseline, matcher, obliques).
//
// Estimate: on a grid of sample pixels of each view v (every `sample_step_px`-th row and column, or sparser on views of
// more than `max_samples_per_view` x sample_step_px^2 pixels), every view b the sample consults
// (core/consulted_views.h) that puts the surface within the gate on v's ray (IntersectRay) gives a residual r = t_b - d
// with E[r^2] = k_v^2 s_v^2 + k_b^2 s_b^2, s_v = z gsd_v(z), s_b = z_b gsd_b(z_b) / |f'|. Per ordered pair (v, b) with
// at least `min_samples` residuals: m = median(r^2 / (s_v^2 + s_b^2)) / 0.4549 (the median of chi^2 with one degree of
// freedom; the median keeps blunders that slip through the gate from inflating it) and a = median(s_v^2 / (s_v^2 +
// s_b^2)), so that a k_v^2 + (1 - a) k_b^2 ~ m. The k_v^2 solve these rows in the least-squares sense (plus a weak pull
// of 1e-3 towards their mean, so views without pairs stay defined); the result is clamped to [0.1, 10] times the median
// k. k is absolute: sigma_v(z) = k_v z gsd_v(z) metres. The gate is gate_gsd local GSDs, in the second pass widened to
// gate_sigmas sigma of each pair's difference (a gate fixed in GSDs cuts the residuals of noisy views off inside their
// noise and understates k).
//
// The residuals come from the combine's secant, whose slope over one GSD scatters them where the noise is large
// (core/depth_combine.h). So with slope_step_sigmas > 0 the estimate is made twice: first with the slope over one
// GSD, then over max(1 GSD, slope_step_sigmas sigma) of the first k, as the combine will take it. F1 at 2x GSD
// against one pass (both with the combine's 2 sigma step): aerial-bench Montpellier 0.9755 -> 0.9754, x2.5
// 0.9395 -> 0.9436, Zurich 0.9654 -> 0.9653, x2.5 0.9083 -> 0.9166, St Barth 0.9416 -> 0.9419, x2.5 0.8566 ->
// 0.8675 (median k there 0.0271 -> 0.0289); our bench (%) city 84.51 -> 84.51, x2.5 50.23 -> 51.17, zurich
// 96.94 -> 96.94, x2.5 74.97 -> 75.72, montpellier 96.00 -> 95.99, x2.5 66.85 -> 68.55. A third pass: St Barth
// x2.5 0.8685, Zurich x2.5 0.9173, St Barth 0.9419 (not worth a third noise stage).
#include <cstdint>
#include <vector>

#include "core/consulted_views.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct ViewNoiseOptions {
  int sample_step_px = 8;     // sample grid spacing, depth-map pixels ...
  // ... widened so that a view has at most about this many samples: the estimate's cost stays bounded on large
  // views and tile windows (issue 13: at step 8 it was 30 % of a Dortmund tile's time). Views and windows up to
  // 2048 x 8^2 = 131,072 pixels keep step 8; an 800 x 600 view gets step 16, a 1.3 Mpx tile window 26, a 50 Mpx
  // view 157. 2,048 rather than 8,192 (2026-11-26, twelfth session): aerial-bench Montpellier's noise stage 0.75 ->
  // 0.21 s, wall 0.90x; F1 at 2x GSD within -0.0006..+0.0003 on the six aerial-bench blocks and -0.01..+0.31 points
  // on our six.
  int max_samples_per_view = 2048;  // <= 0: no cap
  int min_samples = 50;       // residuals a view pair needs to count
  double gate_gsd = 12.0;     // residuals within this many local GSDs count. Not fusion.combine_gate_gsd (4): a gate
                              // that narrow truncates the residuals and halved the estimated noise on blocks with
                              // large errors (aerial-bench Montpellier at error scale 2.5: k 0.0061 against 0.0130)
  // The second pass widens each pair's gate to this many sigma of the pair's difference under the first pass's k
  // (0 = gate_gsd only). With a gate fixed in GSDs, the noisier views' residuals are cut off inside the noise and k
  // comes out low, most for the noisiest: aerial-bench Montpellier x2.5 gave its obliques 0.0143 against the
  // 0.0167 they carry (nadirs 0.0129 against 0.0125), our city x2.5 0.017-0.023 against 0.023 / 0.035. 2.5 sigma
  // (2026-11-27; docs/design.md): our bench x2.5 +1.5 to +3.2 points at
  // 2x GSD, aerial-bench x2.5 +0.0003 to +0.0021, the scale-1 blocks within -0.03 points and +-0.0001.
  double gate_sigmas = 2.5;
  double min_slope = 0.2;     // as DepthCombineOptions::min_slope
  // As DepthCombineOptions::slope_step_sigmas; > 0: a second pass whose secants take their slope over that many
  // sigmas of the first pass's noise (0 = one pass).
  double slope_step_sigmas = kCombineSlopeStepSigmas;
};

// k per view (1 for all when no pair has enough samples: then only equal weights are meant). Deterministic for any thread count.
std::vector<double> EstimateViewNoiseFactors(const std::vector<SacView>& views, const ConsultedViews& combine_views,
                                             const ViewNoiseOptions& options);

}  // namespace sacfuse
