#pragma once
// SAC's "combine" step as refinement (the paper is vague here; see docs/design.md): a pixel that the
// collapse emits from its selected view v keeps v's pixel grid (so the point count stays SAC's), but its depth
// along v's ray becomes the weighted mean of where v's own depth map and every agreeing neighbour depth map put
// the surface on that ray.
//
//  * Neighbour b's surface on v's ray: f(t) = D_b(pi_b(x(t))) - z_b(x(t)), x(t) the point of v's ray at depth t,
//    D_b the depth map of b (bilinear between valid pixels), z_b the point's depth in b. One secant step from the
//    selected depth d: t_b = d - f(d) / f'(d), f' from a second sample one local GSD further along the ray.
//  * Weights: a depth map's z-error grows as z^2 / focal (stereo: sigma_z = z^2 sigma_disparity / (f B)), times a
//    per-view factor k (baseline, matcher quality, oblique or not) that core/view_noise.h estimates from the
//    data; an error e of D_b moves t_b by e / |f'|. So w_b = f'^2 / (k_b z_b gsd_b(z_b))^2 and
//    w_v = 1 / (k_v d gsd_v(d))^2.
//  * Weights actually used (SacOptions::combine_weights, default "view"): 1 / k_i^2 only. Measured on aerial-bench,
//    F1 at 2x GSD, full model -> k only (-> equal): Montpellier 0.9752 -> 0.9760 (0.9758), Montpellier errors x2.5
//    0.9139 -> 0.9292 (0.9301), Zurich 0.9655 -> 0.9659 (0.9657), Zurich x2.5 0.8794 -> 0.8961 (0.8997); the slope
//    alone as weight 0.9077 and z^2/f with the slope but without k 0.9145 (Montpellier x2.5). The full model leans
//    on the own (selected, most precise) depth and on steep intersections, but these blocks' errors are largely
//    per view (pose, smooth bias), which z^2/f does not describe, and the slope is a finite difference of noisy
//    depths. k stays: it is measured from the residuals, so a biased or noisy depth map counts less (equal
//    weights let a view biased by 3.6 GSD pull its neighbours' points; core/sac_fusion_test.cc).
//  * The secant's slope is a finite difference of two noisy depths. With its samples one GSD apart, t_b =
//    d - f(d) / f' extrapolates that difference over |f(d)|, which reaches the gate (several GSDs where the noise is
//    large: aerial-bench at error scale 2.5 has sigma 0.3-0.5 m at 0.125 m GSD), so the depth noise is amplified by
//    |f(d)| / 1 GSD. The second sample therefore lies `slope_step_sigmas` sigma of the own depth further along the
//    ray when that is more than one GSD, and the step nearly interpolates (core/depth_combine_test.cc).
//    Measured, F1 at 2x GSD (step 1 GSD -> 2 sigma -> 3 sigma): aerial-bench Montpellier 0.9760 -> 0.9755 ->
//    0.9751, x2.5 0.9292 -> 0.9395 -> 0.9421, Zurich 0.9659 -> 0.9654 -> 0.9651, x2.5 0.8961 -> 0.9083 -> 0.9127,
//    St Barth 0.9426 -> 0.9416 -> 0.9412, x2.5 0.8380 -> 0.8566 -> 0.8614; our bench (%) city 84.39 -> 84.51 ->
//    84.56, x2.5 48.76 -> 50.23 -> 51.52, zurich 96.91 -> 96.94 -> 96.92, x2.5 73.04 -> 74.97 -> 75.87,
//    montpellier 96.03 -> 96.00 -> 95.95, x2.5 65.23 -> 66.85 -> 68.48 (with a one-pass noise estimate). With the
//    two-pass estimate (core/view_noise.h), 2 -> 3 sigma: Montpellier 0.9754 -> 0.9748, x2.5 0.9436 -> 0.9458,
//    Zurich 0.9653 -> 0.9649, x2.5 0.9166 -> 0.9224, St Barth 0.9419 -> 0.9415, x2.5 0.8675 -> 0.8739: 3 sigma is
//    the default (the sum of F1 over the six blocks +0.013, at most 0.0006 lost at error scale 1). Also tried: a
//    centred difference over +-2 sigma (one more lookup per neighbour: St Barth x2.5 0.8665 but Zurich 0.9643,
//    St Barth 0.9410), and the neighbour's point
//    projected onto the ray instead of the secant (no slope; Montpellier x2.5 0.9376, St Barth x2.5 0.8558, but
//    all three error-scale-1 blocks lower by 0.001-0.005 and our city 83.51: wrong on tilted surfaces).
//  * The surface as a plane (`surface` kPlane, `fusion.combine_surface: plane`, the default since 2026-11-26): where
//    the pixel's superpixel has a fitted plane (its node's normal n) that the ray meets at |cos| >= kPlaneMinCos,
//    the surface point X_b of each neighbour b that sees the point within kPlaneMaxPairAngleDeg of the ray (its
//    bilinear depth at the projection of the ray's point at d, back-projected) is carried along that plane onto
//    the ray: t_b = n.(X_b - C_v) / n.r_v. The secant's slope is a difference of two noisy depths, and its error e
//    moves the hit by e times the own depth's error |d - truth|; along the plane the hit's error is b's depth
//    error plus the normal's error times the lateral distance between X_b and the ray, which is small for
//    near-parallel rays and grows with the angle between them (so wider pairs keep the secant). One depth read
//    instead of two. Measured, F1 at 2x GSD, secant -> plane for every pair -> pairs within 30 deg: aerial-bench
//    Montpellier 0.9748 -> 0.9751 -> 0.9749, x2.5 0.9458 -> 0.9473 -> 0.9469, Zurich 0.9649 -> 0.9654 -> 0.9650,
//    x2.5 0.9224 -> 0.9257 -> 0.9236, St Barth 0.9415 -> 0.9416 -> 0.9414, x2.5 0.8739 -> 0.8763 -> 0.8755; our
//    bench (%) city 84.56 -> 85.15 -> 84.64, x2.5 52.83 -> 51.46 -> 53.10, zurich 96.90 -> 96.87 -> 96.91, x2.5
//    76.85 -> 75.86 -> 77.00, montpellier 95.95 -> 96.05 -> 95.97, x2.5 70.37 -> 69.44 -> 70.76. Every pair gains
//    most on aerial-bench but loses ~1 point on each of our error-scale-2.5 blocks and raises the free-space
//    share at x2.5 (St Barth 3.64 -> 3.93 %; within 30 deg 3.66 %). Pairs within 20 / 40 / 55 deg: our city x2.5
//    53.09 / 53.02 / 52.35, St Barth x2.5 0.8749 / 0.8759 / 0.8763. Elsewhere (no plane, grazing, wide pairs) the
//    secant.
//  * Two passes (`passes`, `fusion.combine_passes: 2`, the default since 2026-11-26): the second finds every
//    neighbour's surface again from the ray's point at the first mean, which lies nearer the surface than the own
//    depth, so the plane carries the neighbour's point less far and the secant extrapolates less; hits must lie
//    within the gate of both that point and the own depth. One pass -> two, F1 at 2x GSD: aerial-bench
//    Montpellier 0.9747 -> 0.9747, x2.5 0.9463 -> 0.9500, Zurich 0.9650 -> 0.9647, x2.5 0.9239 -> 0.9275, St Barth
//    0.9415 -> 0.9413, x2.5 0.8756 -> 0.8823; our bench (%) city 84.63 -> 85.11, x2.5 53.41 -> 53.94, zurich 96.93
//    -> 97.00, x2.5 77.13 -> 77.80, montpellier 95.98 -> 96.19, x2.5 70.92 -> 72.21; free space lower on all six
//    aerial-bench blocks. It costs a second read of every neighbour: aerial-bench Montpellier 1.22x the wall time.
//    `later_pass_gate` (`fusion.combine_later_pass_gate`, default 1: the whole gate) narrows the gate around the
//    previous mean in the later passes: the mean is nearer the surface than the own depth, so a hit far from it
//    is more likely another surface (a facade at a wall's foot, fattening) than noise. Measured 2026-11-26
//    (thirteenth session), factor 1 -> 0.85 / 0.75 / 0.67 / 0.6, F1 at 2x GSD, aerial-bench Montpellier 0.9746 ->
//    0.9750 / 0.9755 / 0.9758 / 0.9759, x2.5 0.9498 -> 0.9505 / 0.9509 / 0.9511 / 0.9510, Zurich 0.9648 -> 0.9651 /
//    0.9654 / 0.9656 / 0.9659, x2.5 0.9283 -> 0.9282 / 0.9274 / 0.9264 / 0.9249, St Barth 0.9431 -> 0.9436 /
//    0.9440 / 0.9442 / 0.9444, x2.5 0.8842 -> 0.8855 / 0.8860 / 0.8857 / 0.8846; but our bench at 0.75 (%) city
//    85.07 -> 84.89, x2.5 53.92 -> 53.33, zurich 96.98 -> 96.96, x2.5 77.74 -> 77.40, montpellier 96.15 -> 96.14,
//    x2.5 72.17 -> 71.81 (its noise is truncated), and no half-way line of issue 12 is crossed, so it is not the
//    default. Only near a depth jump of the own view it keeps most of the aerial-bench gain and still
//    loses 0.1-0.2 points on our error-scale-2.5 blocks.
//    `later_pass_min_shift_gsd` (`fusion.combine_later_pass_min_shift_gsd`, default 1; issue 13): a later pass is
//    made only where the previous one moved the centre by at least this many local GSDs; where it moved less, the
//    later pass would start from almost the same point on the ray and find almost the same surfaces. On a
//    full-scale Dortmund tile 52 % of the first passes move the centre less than 1 GSD (28 % less than 0.5, 83 %
//    less than 2); aerial-bench Montpellier 70 %, its x2.5 block 39 % (noisier depths move further). Measured
//    2026-11-28 (docs/design.md): Dortmund tile 6_6 CPU -4 %; F1 at 2x GSD 0 (always) -> 1 -> 2,
//    aerial-bench Montpellier 0.9765 -> 0.9767 -> 0.9766, x2.5 0.9559 -> 0.9559 -> 0.9558, Zurich 0.9661 ->
//    0.9663 -> 0.9664, x2.5 0.9499 -> 0.9500 -> 0.9493, St Barth 0.9470 -> 0.9470 -> 0.9470, x2.5 0.9144 ->
//    0.9144 -> 0.9136: 1 keeps every block, 2 loses at x2.5.
//  * Robustness: only neighbours whose t_b lies within the gate of d take part (the others see another surface,
//    an occluder or a blunder): `gate_gsd` local GSDs, widened to `gate_sigmas` sigma of v's own depth (k_v d gsd_v(d)) where
//    the estimated noise is larger. Grazing intersections (|f'| < 0.2) are skipped.
//  * Measured on `small` (seed 7), F1 at 2x GSD: select 66.55; average with 10 neighbour views and a 5 GSD gate
//    75.64, 12 GSD 80.32; 24 views 82.78; weights with estimated k 83.44 (the true oblique/nadir ratio of the
//    simulator would give 83.78); 40 views 83.73 (TSDF: 83.59). Tried and dropped: a second, re-centred mean
//    within 3 sigma (+0.03); a 16 GSD gate (small 84.17 but tiny 97.48 -> 96.91); a gate per candidate of
//    3 sigma of the pair's difference (small 82.60, tiny 97.42); the outlier test on the averaged point
//    (small 81.79: it keeps noisy pixels the strict test on the own depth drops).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/sac_tolerance.h"
#include "core/sac_view.h"

namespace sacfuse {

// How the depth maps that take part are weighted (see the header).
enum class CombineWeights {
  kView,   // 1 / k_i^2: the per-view noise factor only (1 for all without noise factors)
  kEqual,  // 1 for every depth map
  kNoise,  // the stereo model: w_v and w_b above
};

// Where a neighbour's surface meets the ray (see the header).
enum class CombineSurface {
  kPlane,   // along the plane of the pixel's superpixel, where it has one that the ray does not graze, for the
            // views within kPlaneMaxPairAngleDeg of the ray
  kSecant,  // one secant step on the neighbour's depth map everywhere
};
// kPlane uses the plane only where |cos(normal, ray)| is at least this (closer to grazing: the secant). Measured
// on aerial-bench with the plane for every pair (F1 at 2x GSD, St Barth x2.5 / Montpellier x2.5 / Montpellier):
// 0.15 0.8717 / 0.9426 / 0.9752, 0.3 0.8763 / 0.9473 / 0.9751, 0.6 0.8771 / 0.9475 / 0.9746.
inline constexpr double kPlaneMinCos = 0.3;
// kPlane carries a neighbour's surface along the plane only when its ray to the point is within this angle of the
// pixel's ray (wider: the secant); measurements in the header.
inline constexpr double kPlaneMaxPairAngleDeg = 30.0;

struct DepthCombineOptions {
  double gate_gsd = 12.0;     // neighbours farther than this many local GSDs along the ray are ignored ...
  double gate_sigmas = 3.0;   // ... unless within this many sigmas of the own depth (with noise factors)
  double min_slope = 0.2;     // |f'| below this (grazing ray-surface intersection) is ignored
  // f' from a second sample max(1 local GSD, this x sigma of the own depth) further along the ray (with noise
  // factors; 0 = always 1 GSD)
  double slope_step_sigmas = kCombineSlopeStepSigmas;
  CombineWeights weights = CombineWeights::kView;
  CombineSurface surface = CombineSurface::kPlane;
  // Passes: the second and later find the neighbours' surfaces again from the previous pass's mean, within this
  // fraction of the gate of it and within the gate of the own depth (see the header).
  int passes = 2;
  double later_pass_gate = 1.0;
  // A later pass is made only when the previous one moved the centre by at least this many local GSDs (0 = always).
  double later_pass_min_shift_gsd = kCombineLaterPassMinShiftGsd;
};

// Depth of `depth` at image coordinates (u, v) (corner convention), bilinear over the 2x2 pixel centres around
// it when all four are valid and within `max_spread_m` of each other, else the depth of the nearest valid one of
// those centres (the pixel holding (u, v) when it is valid); false when (u, v) is outside or none is valid.
// Measured (2026-11-27), against the pixel holding (u, v) alone: our bench F1 at 2x GSD (%) city 85.07 -> 85.22,
// x2.5 53.92 -> 54.27, zurich 96.98 -> 97.02, x2.5 77.74 -> 78.03, montpellier 96.15 -> 96.20, x2.5 72.17 ->
// 72.63 (its depth maps have scattered invalid pixels, and a view whose projection hit one was left out of the
// mean); aerial-bench within +-0.0001 on all six blocks.
bool SampleDepth(const DepthMap& depth, double u, double v, double max_spread_m, double* depth_m);

// Where depth map b puts the surface on a ray of another view (the secant step of the header).
struct RayHit {
  double depth_m = 0.0;   // t_b, along the ray's view
  double slope = 0.0;     // f'(d)
  double z_b_m = 0.0;     // the point's depth in b
};
// The two points at which the secant samples the ray of image point (u, v) of `view` (corner convention): at depth
// `depth_m` and `depth_m` + `step_m` (x(t) = world_from_cam * (ray_cam * t), ray_cam with unit z).
struct SecantPoints {
  Eigen::Vector3d at_depth, at_next;
};
SecantPoints SecantPointsOnRay(const SacView& view, double u, double v_px, double depth_m, double step_m);

// `at_depth_in_b` and `at_next` are the ray's points at depth d (projected into b: ProjectIntoView) and d + step_m
// (SecantPointsOnRay); false when b has no surface there, its surface is more than `max_offset_m` away, or the
// intersection is grazing (|f'| < min_slope).
bool IntersectRay(const SacView& b, const ViewPoint& at_depth_in_b, const Eigen::Vector3d& at_next, double depth_m,
                  double step_m, double max_offset_m, double min_slope, RayHit* hit);

// The ray x(t) = centre + t * direction of a view's pixel (t its z-depth: direction has unit z in the camera).
struct PixelRay {
  Eigen::Vector3d centre_in_world, direction_in_world;
};
PixelRay PixelRayOf(const SacView& view, double u, double v_px);

// Where depth map b's surface point at `at_depth_in_b` (the ray's point at depth d projected into b), carried along
// the plane with normal `normal_in_world`, meets `ray` (CombineSurface::kPlane). The same rejections as
// IntersectRay except the slope's (the caller checks that the ray does not graze the plane); hit->slope is the
// plane's f'(d) = -(n.r_v) / (n.r_b), for weights that use it.
bool IntersectPlane(const SacView& b, const ViewPoint& at_depth_in_b, const PixelRay& ray,
                    const Eigen::Vector3d& normal_in_world, double depth_m, double max_offset_m, RayHit* hit);

// The most views a combine or a noise estimate consults per point (SacOptions::combine_max_views is at most 64);
// CheckCombineViewCount throws std::invalid_argument for more.
inline constexpr size_t kMaxCombineViews = 64;
void CheckCombineViewCount(size_t num_views);

// The ray's first secant sample (SecantPoints::at_depth) projected into each of views[ids[i]], into at[i], and the
// depth pixels around it prefetched, so that the IntersectRay reads which follow overlap their cache misses
// (CombineDepth and the noise estimate). `at` holds ids.size() entries, at most kMaxCombineViews.
inline void ProjectForSecants(const std::vector<SacView>& views, const std::vector<uint32_t>& ids,
                              const Eigen::Vector3d& at_depth, ViewPoint* at) {
  for (size_t i = 0; i < ids.size(); ++i) {
    at[i] = ProjectIntoView(views[ids[i]], at_depth);
    PrefetchDepthAround(views[ids[i]], at[i]);
  }
}

struct CombinedDepth {
  double depth_m = 0.0;   // refined depth along the view's ray (the input depth when nothing agreed)
  int support = 1;        // depth maps that took part, the own one included
  // The other depth maps' part of the last pass: their summed weight and their weighted mean depth along the ray
  // (0 when none agreed), so depth_m = (w_own d + others_weight others_depth_m) / (w_own + others_weight).
  double others_weight = 0.0;
  double others_depth_m = 0.0;
};

// The weight of depth map i in the mean, whose z-depth at the point is z_m and whose intersection with the ray
// has slope `slope` (1 for the own depth): DepthCombineOptions::weights (header). noise_factor empty = 1 for all.
double CombineWeight(const std::vector<SacView>& views, uint32_t i, double z_m, double slope,
                     const std::vector<double>& noise_factor, CombineWeights weights);

// The gate of the own depth `depth_m` of view v: DepthCombineOptions::gate_gsd local GSDs, widened to gate_sigmas
// sigma of the own depth's estimated noise.
double CombineGateM(const std::vector<SacView>& views, uint32_t v, double depth_m,
                    const std::vector<double>& noise_factor, const DepthCombineOptions& options);

// Refines depth `depth_m` of pixel centre (u, v) of `views[v]` with the depth maps of `neighbors` (indices into
// `views`). `noise_factor[i]` is k of view i (empty = 1 for all). `plane_normal_in_world`: the normal of the plane
// fitted to the pixel's superpixel, for CombineSurface::kPlane; zero = none (the secant).
CombinedDepth CombineDepth(const std::vector<SacView>& views, uint32_t v, double u, double v_px, double depth_m,
                           const std::vector<uint32_t>& neighbors, const std::vector<double>& noise_factor,
                           const DepthCombineOptions& options,
                           const Eigen::Vector3d& plane_normal_in_world = Eigen::Vector3d::Zero());

}  // namespace sacfuse
