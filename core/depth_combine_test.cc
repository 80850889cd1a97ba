#include "core/depth_combine.h"

#include <cmath>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "core/method_test_scene.h"
#include "core/sac_test_scene.h"
#include "core/view_noise.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::kGroundZ;
using testing::kNadirGsdM;
using testing::kNadirHeightM;
using testing::kNorth;
using testing::kWholePixelShiftM;
using testing::MethodBlock;
using testing::NadirView;
using testing::PlaneDepth;

TEST(SampleDepthTest, BilinearBetweenValidCentresNearestOtherwise) {
  DepthMap d(3, 3, 1, 10.0f);
  d.at(0, 0) = 10.0f;
  d.at(0, 1) = 12.0f;
  d.at(1, 0) = 14.0f;
  d.at(1, 1) = 16.0f;
  double z = 0;
  // (1.0, 1.0) is the middle of the four centres (0.5, 0.5) .. (1.5, 1.5): their mean.
  ASSERT_TRUE(SampleDepth(d, 1.0, 1.0, 100.0, &z));
  EXPECT_NEAR(z, 13.0, 1e-9);
  // On a pixel centre: that pixel.
  ASSERT_TRUE(SampleDepth(d, 1.5, 0.5, 100.0, &z));
  EXPECT_NEAR(z, 12.0, 1e-9);
  // The four differ by 6 m > 5 m allowed: the nearest pixel's depth (pixel (1, 1) holds (1.0, 1.0)).
  ASSERT_TRUE(SampleDepth(d, 1.0, 1.0, 5.0, &z));
  EXPECT_NEAR(z, 16.0, 1e-9);
  // One of the four invalid: nearest.
  d.at(0, 0) = 0.0f;
  ASSERT_TRUE(SampleDepth(d, 1.2, 1.2, 100.0, &z));
  EXPECT_NEAR(z, 16.0, 1e-9);
  // The pixel holding (u, v), (1, 1), invalid: the nearest valid centre of the four, (0.5, 1.5) of pixel (1, 0)
  // (pixel (0, 1) is valid too but its centre is farther from (1.2, 1.4)).
  d.at(1, 1) = 0.0f;
  ASSERT_TRUE(SampleDepth(d, 1.2, 1.4, 100.0, &z));
  EXPECT_NEAR(z, 14.0, 1e-9);
  // None of the four valid, or outside: no depth.
  d.at(0, 1) = 0.0f;
  d.at(1, 0) = 0.0f;
  EXPECT_FALSE(SampleDepth(d, 1.0, 1.0, 100.0, &z));
  EXPECT_FALSE(SampleDepth(d, 0.4, 0.4, 100.0, &z));
  EXPECT_FALSE(SampleDepth(d, 3.2, 1.0, 100.0, &z));
  EXPECT_FALSE(SampleDepth(d, -0.1, 1.0, 100.0, &z));
}

// Two nadir views of the plane z = ground + kTiltSlope (x - kEast): a (index 0) with its exact depth map, b (index
// 1, one pixel's shift east) with its exact depth map changed by `perturb_b`; and three pixels of a to test at.
constexpr double kTiltSlope = 0.3;
constexpr std::pair<int, int> kTiltedTestPixels[] = {{45, 80}, {20, 100}, {70, 60}};
struct TiltedPlanePair {
  MethodBlock block;
  std::vector<SacView> views;
  template <typename Perturb>
  explicit TiltedPlanePair(Perturb perturb_b) {
    const View a = NadirView(0, kEast, kNorth, kNadirHeightM);
    const View b = NadirView(1, kEast + kWholePixelShiftM, kNorth, kNadirHeightM);
    block.Add(a, testing::TiltedPlaneDepth(a, kGroundZ, kEast, kTiltSlope));
    DepthMap b_depth = testing::TiltedPlaneDepth(b, kGroundZ, kEast, kTiltSlope);
    perturb_b(&b_depth);
    block.Add(b, b_depth);
    views = block.SacViews();
  }
};

TEST(IntersectRayTest, FindsWhereAnotherDepthMapPutsATiltedSurfaceOnTheRay) {
  // View b's depth map is 0.5 m too long (surface 0.5 m too low). On a's ray, b's surface is where a would see the
  // plane lowered by 0.5 m.
  const TiltedPlanePair s([](DepthMap* depth) {
    for (float& z : depth->data) z += 0.5f;
  });
  const auto& views = s.views;
  const DepthMap lowered = testing::TiltedPlaneDepth(s.block.views[0], kGroundZ - 0.5, kEast, kTiltSlope);
  for (const auto& [row, col] : kTiltedTestPixels) {
    const double d = s.block.depths[0].at(row, col);
    const double gsd = views[0].GsdAt(d);
    const Eigen::Vector3d ray = views[0].depth_camera.Unproject(col + 0.5, row + 0.5, 1.0);
    RayHit hit;
    const ViewPoint at_depth = ProjectIntoView(views[1], views[0].world_from_cam * (ray * d));
    const Eigen::Vector3d at_next = views[0].world_from_cam * (ray * (d + gsd));
    ASSERT_TRUE(IntersectRay(views[1], at_depth, at_next, d, gsd, 12 * gsd, 0.2, &hit)) << row << " " << col;
    EXPECT_NEAR(hit.depth_m, lowered.at(row, col), 0.01) << row << " " << col;
    // A gate narrower than the 0.5 m offset rejects it.
    EXPECT_FALSE(IntersectRay(views[1], at_depth, at_next, d, gsd, 0.2, 0.2, &hit));
  }
}

TEST(IntersectPlaneTest, CarriesTheNeighboursSurfacePointAlongThePlaneOntoTheRay) {
  // The plane's normal is (-0.3, 0, 1). b's depth map is exact except for a checkerboard of +-0.2 m; a's own depth
  // is 1 m too long. Carried along the exact plane, b's surface point lands on a's ray within the 0.2 m of b's
  // error (the rays are near-parallel, so the plane hardly scales it), whatever a's own error.
  const TiltedPlanePair s([](DepthMap* depth) {
    for (int r = 0; r < depth->height; ++r) {
      for (int c = 0; c < depth->width; ++c) depth->at(r, c) += (r + c) % 2 == 0 ? 0.2f : -0.2f;
    }
  });
  const auto& views = s.views;
  const Eigen::Vector3d normal(-kTiltSlope, 0.0, 1.0);
  for (const auto& [row, col] : kTiltedTestPixels) {
    const double truth = s.block.depths[0].at(row, col);
    const double d = truth + 1.0;
    const PixelRay ray = PixelRayOf(views[0], col + 0.5, row + 0.5);
    const ViewPoint at_depth = ProjectIntoView(views[1], ray.centre_in_world + ray.direction_in_world * d);
    RayHit hit;
    ASSERT_TRUE(IntersectPlane(views[1], at_depth, ray, normal, d, 2.0, &hit)) << row << " " << col;
    EXPECT_NEAR(hit.depth_m, truth, 0.21) << row << " " << col;
    EXPECT_LT(hit.slope, 0.0);  // f decreases along the ray: b's surface lies ahead of the point before it
    // The same with the own depth exact: b's error only.
    const ViewPoint at_truth = ProjectIntoView(views[1], ray.centre_in_world + ray.direction_in_world * truth);
    ASSERT_TRUE(IntersectPlane(views[1], at_truth, ray, normal, truth, 2.0, &hit));
    EXPECT_NEAR(hit.depth_m, truth, 0.21);
    // A gate narrower than the 1 m between the own depth and the surface rejects it.
    EXPECT_FALSE(IntersectPlane(views[1], at_depth, ray, normal, d, 0.5, &hit));
  }
}

// Nadir views (four in most tests) of a flat ground at the same height (so equal z gsd(z)), each offset along
// its depth by depth_offsets_m[i], shifted by whole pixels.
struct FourViews {
  MethodBlock block;
  std::vector<SacView> views;
  explicit FourViews(const std::vector<double>& depth_offsets_m) {
    for (size_t i = 0; i < depth_offsets_m.size(); ++i) {
      const View v = NadirView(static_cast<uint32_t>(i), kEast + i * kWholePixelShiftM / 4, kNorth, kNadirHeightM);
      block.Add(v, PlaneDepth(v, depth_offsets_m[i]));
    }
    views = block.SacViews();
  }
};

// Independent per-pixel depth noise of sigma_m[i] metres on view i of `s` (fixed seed).
void AddDepthNoise(const double (&sigma_m)[4], unsigned seed, FourViews* s) {
  std::mt19937 rng(seed);
  for (size_t i = 0; i < 4; ++i) testing::AddDepthNoise(&s->block.depths[i], sigma_m[i], &rng);
}
// Each of the four views combined with the three others.
const std::vector<std::vector<uint32_t>> kFourViewsOthers = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

TEST(CombineDepthTest, AveragesAgreeingViewsEquallyOrByNoiseAndGatesOutOthers) {
  // View 0 exact; 1: +0.3 m; 2: -0.3 m; 3: a 5 m blunder (beyond 12 GSDs = 2 m).
  FourViews s({0.0, 0.3, -0.3, 5.0});
  const int row = 45, col = 60;
  const double d = s.block.depths[0].at(row, col);
  DepthCombineOptions options;
  options.gate_gsd = 12.0;
  ASSERT_LT(12.0 * kNadirGsdM, 5.0);
  CombinedDepth c = CombineDepth(s.views, 0, col + 0.5, row + 0.5, d, {1, 2, 3}, {}, options);
  EXPECT_EQ(c.support, 3);
  EXPECT_NEAR(c.depth_m, d, 1e-4);  // (0 + 0.3 - 0.3) / 3
  // Absolute noise factors: sigma 0.1 m for views 0, 1 and 3, view 2 three times noisier. Equal weights: still
  // (0 + 0.3 - 0.3) / 3. View weights, and here (equal depths, slope 1) also the noise model: view 2 weighs 1/9,
  // (0 + 0.3 - 0.3 / 9) / (2 + 1 / 9). The gate stays 12 GSDs (3 sigma is less), so the blunder stays out.
  const double k = 0.1 / DepthNoiseScale(s.views[0], d);
  options.weights = CombineWeights::kEqual;
  c = CombineDepth(s.views, 0, col + 0.5, row + 0.5, d, {1, 2, 3}, {k, k, 3 * k, k}, options);
  EXPECT_EQ(c.support, 3);
  EXPECT_NEAR(c.depth_m, d, 1e-4);
  options.weights = CombineWeights::kNoise;
  c = CombineDepth(s.views, 0, col + 0.5, row + 0.5, d, {1, 2, 3}, {k, k, 3 * k, k}, options);
  EXPECT_EQ(c.support, 3);
  EXPECT_NEAR(c.depth_m - d, (0.3 - 0.3 / 9) / (2 + 1.0 / 9), 1e-4);
  options.weights = CombineWeights::kView;
  c = CombineDepth(s.views, 0, col + 0.5, row + 0.5, d, {1, 2, 3}, {k, k, 3 * k, k}, options);
  EXPECT_EQ(c.support, 3);
  EXPECT_NEAR(c.depth_m - d, (0.3 - 0.3 / 9) / (2 + 1.0 / 9), 1e-4);
  // Very noisy depth maps (sigma 2 m) widen the gate to 3 sigma = 6 m: the 5 m depth takes part.
  c = CombineDepth(s.views, 0, col + 0.5, row + 0.5, d, {1, 2, 3}, {20 * k, 20 * k, 20 * k, 20 * k}, options);
  EXPECT_EQ(c.support, 4);
  EXPECT_NEAR(c.depth_m - d, 5.0 / 4, 1e-3);
  // No neighbours: the depth as it was.
  c = CombineDepth(s.views, 0, col + 0.5, row + 0.5, d, {}, {}, options);
  EXPECT_EQ(c.support, 1);
  EXPECT_NEAR(c.depth_m, d, 1e-9);
}

TEST(ViewNoiseTest, RecoversTheRatioOfDepthNoiseBetweenViews) {
  // Views 0-1 have depth noise sigma 0.2 m, views 2-3 0.4 m (independent per pixel, fixed seed); all at the same
  // height, so k must come out in the ratio 1 : 2.
  FourViews s({0.0, 0.0, 0.0, 0.0});
  AddDepthNoise({0.2, 0.2, 0.4, 0.4}, 7, &s);
  const std::vector<std::vector<uint32_t>>& others = kFourViewsOthers;
  ViewNoiseOptions options;
  options.sample_step_px = 2;
  options.max_samples_per_view = 0;  // the whole step-2 grid (the cap is tested below)
  const std::vector<double> k = EstimateViewNoiseFactors(s.views, ConsultedViews(others), options);
  ASSERT_EQ(k.size(), 4u);
  EXPECT_NEAR(k[1] / k[0], 1.0, 0.15);
  EXPECT_NEAR(k[3] / k[2], 1.0, 0.15);
  EXPECT_NEAR((k[2] + k[3]) / (k[0] + k[1]), 2.0, 0.3);
  // Absolute: sigma = k z gsd(z) metres.
  const double scale = DepthNoiseScale(s.views[0], kNadirHeightM);
  EXPECT_NEAR(k[0] * scale, 0.2, 0.03);
  EXPECT_NEAR(k[2] * scale, 0.4, 0.06);
  // Without overlapping views there is nothing to estimate: all 1.
  const std::vector<double> alone = EstimateViewNoiseFactors(s.views, ConsultedViews({{}, {}, {}, {}}), options);
  for (double x : alone) EXPECT_EQ(x, 1.0);
  // The sample cap widens the step on these 120 x 90 views: ~300 samples per view (step 6) still give the ratio;
  // ~20 (step 24) leave every pair below min_samples (50), so nothing is estimated.
  options.max_samples_per_view = 300;
  const std::vector<double> capped = EstimateViewNoiseFactors(s.views, ConsultedViews(others), options);
  ASSERT_EQ(capped.size(), 4u);
  EXPECT_NEAR((capped[2] + capped[3]) / (capped[0] + capped[1]), 2.0, 0.4);
  options.max_samples_per_view = 20;
  for (double x : EstimateViewNoiseFactors(s.views, ConsultedViews(others), options)) EXPECT_EQ(x, 1.0);
}

// Wide nadir views (f = 300 px at 100 m: GSD 0.33 m) with baselines of 0.5-1 flying heights, so one GSD along a
// ray moves its projection by 0.5-1 px in the others. Views 1-6 (and view 0 with `noisy_own`) carry independent
// per-pixel depth noise of sigma = 0.5 m (fixed seed).
struct WideViews {
  static constexpr double kHeightM = 100.0, kNoiseM = 0.5;
  MethodBlock block;
  std::vector<SacView> views;
  explicit WideViews(bool noisy_own) {
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, kNoiseM);
    const std::vector<double> shifts_m = {0.0, -100.0, -50.0, 50.0, 100.0, -75.0, 75.0};
    for (size_t i = 0; i < shifts_m.size(); ++i) {
      const View view = NadirView(static_cast<uint32_t>(i), kEast + shifts_m[i], kNorth, kHeightM, 400, 200, 300.0);
      DepthMap depth = PlaneDepth(view);
      if (i > 0 || noisy_own) {
        for (float& z : depth.data) z += static_cast<float>(noise(rng));
      }
      block.Add(view, depth);
    }
    views = block.SacViews();
  }
};

TEST(CombineDepthTest, SlopeOverTheNoiseNotOneGsdKeepsNoisyNeighboursFromScattering) {
  // The own depth is exact but 1 m (2 sigma) too long. A secant over one GSD extrapolates the difference of two
  // noisy depths by |f(d)| / 1 GSD; over 2 sigma (1 m) it nearly interpolates, and the averaged depth lies closer
  // to the ground.
  constexpr double kOffsetM = 1.0;
  const WideViews s(false);
  const double k = WideViews::kNoiseM / DepthNoiseScale(s.views[0], WideViews::kHeightM);
  const std::vector<double> factors(s.views.size(), k);
  const std::vector<uint32_t> neighbors = {1, 2, 3, 4, 5, 6};
  auto rms_error = [&](double slope_step_sigmas) {
    DepthCombineOptions options;
    options.gate_gsd = 4.0;
    options.slope_step_sigmas = slope_step_sigmas;
    double sum = 0;
    int n = 0;
    for (int row = 60; row < 140; row += 4) {
      for (int col = 160; col < 240; col += 4) {
        const double truth = s.block.depths[0].at(row, col);
        const CombinedDepth c =
            CombineDepth(s.views, 0, col + 0.5, row + 0.5, truth + kOffsetM, neighbors, factors, options);
        sum += (c.depth_m - truth) * (c.depth_m - truth);
        ++n;
      }
    }
    return std::sqrt(sum / n);
  };
  const double one_gsd = rms_error(0.0), two_sigma = rms_error(2.0);
  // Measured: 0.746 m over one GSD, 0.590 m over 2 sigma (seed 11).
  EXPECT_LT(two_sigma, 0.85 * one_gsd) << one_gsd << " " << two_sigma;
}

TEST(CombineDepthTest, ThePlaneKeepsTheAveragedDepthFromFollowingTheOwnError) {
  // As above (own depth exact but 1 m too long, six neighbours with sigma 0.5 m), against the secant over 3 sigma:
  // along the superpixel's plane (here the ground, normal up) the neighbours' hits do not carry the secant's slope
  // error times the 1 m, and the gate does not favour those pulled towards the own depth.
  constexpr double kOffsetM = 1.0;
  const WideViews s(false);
  const double k = WideViews::kNoiseM / DepthNoiseScale(s.views[0], WideViews::kHeightM);
  const std::vector<double> factors(s.views.size(), k);
  const std::vector<uint32_t> neighbors = {1, 2, 3, 4, 5, 6};
  auto errors = [&](CombineSurface surface, double* mean_m, double* rms_m) {
    DepthCombineOptions options;
    options.gate_gsd = 4.0;
    options.slope_step_sigmas = 3.0;
    options.surface = surface;
    options.passes = 1;
    double sum = 0, sum_sq = 0;
    int n = 0;
    for (int row = 60; row < 140; row += 4) {
      for (int col = 160; col < 240; col += 4) {
        const double truth = s.block.depths[0].at(row, col);
        const CombinedDepth c = CombineDepth(s.views, 0, col + 0.5, row + 0.5, truth + kOffsetM, neighbors, factors,
                                             options, Eigen::Vector3d(0.0, 0.0, 1.0));
        sum += c.depth_m - truth;
        sum_sq += (c.depth_m - truth) * (c.depth_m - truth);
        ++n;
      }
    }
    *mean_m = sum / n;
    *rms_m = std::sqrt(sum_sq / n);
  };
  double secant_mean = 0, secant_rms = 0, plane_mean = 0, plane_rms = 0;
  errors(CombineSurface::kSecant, &secant_mean, &secant_rms);
  errors(CombineSurface::kPlane, &plane_mean, &plane_rms);
  // The own depth alone would give 1 m; six unbiased neighbours with the own depth, 1/7 m (the 1.5 m gate still
  // drops the hits beyond it). Views 2 and 3 (50 m off, ~27 deg) see the point within 30 deg of the ray and are
  // carried along the plane; views 1 and 4-6 (75-100 m off, 37-45 deg) keep the secant. Measured (seed 11): mean
  // error 0.367 m with the plane, 0.492 m by the secant alone; rms 0.400 against 0.535 m.
  EXPECT_LT(plane_rms, 0.8 * secant_rms) << plane_rms << " " << secant_rms;
  EXPECT_LT(std::abs(plane_mean), 0.8 * std::abs(secant_mean)) << plane_mean << " " << secant_mean;
  // A plane the ray grazes (normal across the ray) is not used: the secant's result.
  DepthCombineOptions options;
  options.gate_gsd = 4.0;
  options.slope_step_sigmas = 3.0;
  options.surface = CombineSurface::kPlane;
  options.passes = 1;
  const double truth = s.block.depths[0].at(100, 200);
  const CombinedDepth grazing = CombineDepth(s.views, 0, 200.5, 100.5, truth + kOffsetM, neighbors, factors, options,
                                             Eigen::Vector3d(1.0, 0.0, 0.0));
  options.surface = CombineSurface::kSecant;
  const CombinedDepth secant = CombineDepth(s.views, 0, 200.5, 100.5, truth + kOffsetM, neighbors, factors, options);
  EXPECT_EQ(grazing.depth_m, secant.depth_m);
}

// Flat ground seen from 100 m by the own view and two exact neighbours 40 and 50 m east (22-27 deg: along the
// plane); the pixel's plane normal is 10 deg off.
struct WrongPlaneScene {
  WrongPlaneScene() {
    const double shifts_m[3] = {0.0, 40.0, 50.0};
    for (uint32_t i = 0; i < 3; ++i) {
      const View view = NadirView(i, kEast + shifts_m[i], kNorth, 100.0, 400, 200, 300.0);
      block.Add(view, PlaneDepth(view));
    }
    views = block.SacViews();
    truth_m = block.depths[0].at(kRow, kCol);
  }
  // The combined depth of pixel (kRow, kCol) from the own depth `own_m`.
  double Combine(double own_m, const DepthCombineOptions& options, const Eigen::Vector3d& normal) const {
    return CombineDepth(views, 0, kCol + 0.5, kRow + 0.5, own_m, {1, 2}, {}, options, normal).depth_m;
  }
  static constexpr int kRow = 100, kCol = 200;
  const Eigen::Vector3d tilted{std::sin(10.0 * M_PI / 180.0), 0.0, std::cos(10.0 * M_PI / 180.0)};
  MethodBlock block;
  std::vector<SacView> views;
  double truth_m = 0.0;
};

TEST(CombineDepthTest, ASecondPassFromTheMeanCarriesTheNeighboursLessFar) {
  // The own depth is 1 m too long: the first pass carries each neighbour's surface point ~0.4-0.5 m along the
  // wrong plane; the second starts from the first mean, nearer the ground, carries it less far and lands nearer.
  // With the true normal both passes are exact for the neighbours.
  const WrongPlaneScene s;
  DepthCombineOptions options;
  options.gate_gsd = 12.0;
  auto error = [&](int passes, const Eigen::Vector3d& normal) {
    options.passes = passes;
    return s.Combine(s.truth_m + 1.0, options, normal) - s.truth_m;
  };
  const double one = error(1, s.tilted), two = error(2, s.tilted);
  // The own depth's 1 m weighs a third of each mean (1/3 m); what the wrong plane adds shrinks with the pass.
  // Measured: 0.281 m after one pass, 0.319 m after two.
  EXPECT_LT(std::abs(two - 1.0 / 3.0), 0.5 * std::abs(one - 1.0 / 3.0)) << one << " " << two;
  EXPECT_GT(std::abs(one - 1.0 / 3.0), 0.02) << one;
  EXPECT_NEAR(error(1, Eigen::Vector3d::UnitZ()), 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(error(2, Eigen::Vector3d::UnitZ()), 1.0 / 3.0, 1e-3);
}

TEST(CombineDepthTest, ALaterPassOnlyWhereThePreviousMovedTheCentreFarEnough) {
  // The scene of the test above: the first pass moves the centre from the own depth (1 m long) by 0.719 m, 2.13
  // local GSDs (101 m / 300 px = 0.337 m). A second pass is made when that is at least the minimum shift.
  const WrongPlaneScene s;
  const double own_m = s.truth_m + 1.0;
  DepthCombineOptions options;
  options.gate_gsd = 12.0;
  auto combined = [&](int passes, double min_shift_gsd) {
    options.passes = passes;
    options.later_pass_min_shift_gsd = min_shift_gsd;
    return s.Combine(own_m, options, s.tilted);
  };
  const double one = combined(1, 0.0), two = combined(2, 0.0);
  const double gsd_m = s.views[0].GsdAt(own_m);
  ASSERT_GT(std::abs(one - own_m), 2.0 * gsd_m);
  ASSERT_LT(std::abs(one - own_m), 2.3 * gsd_m);
  ASSERT_GT(std::abs(two - one), 0.01);
  EXPECT_EQ(combined(2, 2.5), one);  // moved less than 2.5 GSD: converged, no second pass
  EXPECT_EQ(combined(2, 2.0), two);  // moved more than 2 GSD: the second pass
  EXPECT_EQ(combined(2, kCombineLaterPassMinShiftGsd), two);
  EXPECT_EQ(combined(4, 2.5), one);
  EXPECT_EQ(DepthCombineOptions().later_pass_min_shift_gsd, kCombineLaterPassMinShiftGsd);
}

TEST(CombineDepthTest, LaterPassesTakeTheNeighboursWithinTheirGateOfTheMean) {
  // The own view and eight neighbours exact, a ninth 0.95 gate long (another surface just inside the gate). The
  // first pass takes all ten: mean 0.095 gate. Seen from there the ninth lies 0.855 gate away: a second pass with
  // the whole gate keeps it (the same mean), one with 0.75 of the gate drops it and lands on the surface.
  const double gate_m = 12.0 * kNadirGsdM;
  std::vector<double> offsets_m(10, 0.0);
  offsets_m[9] = 0.95 * gate_m;
  FourViews s(offsets_m);
  const int row = 45, col = 115;  // view i sees it 12 i pixels further west: all ten inside
  const double d = s.block.depths[0].at(row, col);
  DepthCombineOptions options;
  options.gate_gsd = 12.0;
  options.weights = CombineWeights::kEqual;
  const std::vector<uint32_t> neighbours = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  auto combine = [&](int passes, double later_pass_gate) {
    options.passes = passes;
    options.later_pass_gate = later_pass_gate;
    return CombineDepth(s.views, 0, col + 0.5, row + 0.5, d, neighbours, {}, options);
  };
  CombinedDepth c = combine(1, 0.75);
  EXPECT_EQ(c.support, 10);
  EXPECT_NEAR(c.depth_m - d, 0.095 * gate_m, 1e-3);
  c = combine(2, 1.0);
  EXPECT_EQ(c.support, 10);
  EXPECT_NEAR(c.depth_m - d, 0.095 * gate_m, 1e-3);
  c = combine(2, 0.75);
  EXPECT_EQ(c.support, 9);
  EXPECT_NEAR(c.depth_m, d, 1e-3);
}

TEST(ViewNoiseTest, SecondPassWithTheCombinesSlopeStep) {
  // All seven views with sigma 0.5 m. One pass takes its secants' slope over one GSD; the second over 2 sigma of
  // the first estimate, like the combine, and comes closer to the true noise.
  const WideViews s(true);
  std::vector<std::vector<uint32_t>> others(s.views.size());
  for (uint32_t a = 0; a < s.views.size(); ++a) {
    for (uint32_t b = 0; b < s.views.size(); ++b) {
      if (a != b) others[a].push_back(b);
    }
  }
  ViewNoiseOptions options;
  options.sample_step_px = 4;
  options.max_samples_per_view = 0;  // the whole step-4 grid (the default cap would widen it on 400 x 200 views)
  options.slope_step_sigmas = 0.0;
  const std::vector<double> one_pass = EstimateViewNoiseFactors(s.views, ConsultedViews(others), options);
  options.slope_step_sigmas = 2.0;
  const std::vector<double> two_passes = EstimateViewNoiseFactors(s.views, ConsultedViews(others), options);
  const double scale = DepthNoiseScale(s.views[0], WideViews::kHeightM);
  ASSERT_EQ(one_pass.size(), s.views.size());
  ASSERT_EQ(two_passes.size(), s.views.size());
  // Measured sigma (m), one pass -> two: 0.344 -> 0.390, 0.413 -> 0.436, 0.385 -> 0.397, 0.377 -> 0.408, 0.425 ->
  // 0.448, 0.422 -> 0.455, 0.436 -> 0.465 (bilinear sampling of independent pixel noise understates it).
  double error_one = 0, error_two = 0;
  for (size_t v = 0; v < s.views.size(); ++v) {
    EXPECT_GT(two_passes[v], one_pass[v]) << v;
    EXPECT_LT(two_passes[v] * scale, WideViews::kNoiseM) << v;
    error_one += std::abs(one_pass[v] * scale - WideViews::kNoiseM);
    error_two += std::abs(two_passes[v] * scale - WideViews::kNoiseM);
  }
  EXPECT_LT(error_two, 0.8 * error_one);
}

TEST(ViewNoiseTest, TheSecondPassGateFollowsTheNoise) {
  // Views 0-1 sigma 0.2 m, views 2-3 0.8 m: the difference of 2 and 3 has sigma 1.13 m, and the 12 GSD gate (2 m)
  // cuts it off at 1.8 sigma, so a gate fixed in GSDs understates their noise. The second pass's gate of 2.5 sigma
  // of each pair (under the first pass's k) lets their residuals in.
  FourViews s({0.0, 0.0, 0.0, 0.0});
  const double sigma[4] = {0.2, 0.2, 0.8, 0.8};
  AddDepthNoise(sigma, 5, &s);
  ASSERT_NEAR(12.0 * kNadirGsdM, 2.0, 0.01);
  const std::vector<std::vector<uint32_t>>& others = kFourViewsOthers;
  ViewNoiseOptions options;
  options.sample_step_px = 2;
  options.max_samples_per_view = 0;
  options.gate_sigmas = 0.0;
  const std::vector<double> fixed_gate = EstimateViewNoiseFactors(s.views, ConsultedViews(others), options);
  options.gate_sigmas = 2.5;
  const std::vector<double> noise_gate = EstimateViewNoiseFactors(s.views, ConsultedViews(others), options);
  ASSERT_EQ(fixed_gate.size(), 4u);
  ASSERT_EQ(noise_gate.size(), 4u);
  // Measured sigma (m), fixed gate -> noise gate: 0.295 -> 0.241, 0.284 -> 0.226, 0.750 -> 0.790, 0.760 -> 0.799
  // (the truncated pairs also bias the quiet views' share of the least-squares solve upwards).
  const double scale = DepthNoiseScale(s.views[0], kNadirHeightM);
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_LT(std::abs(noise_gate[v] * scale - sigma[v]), std::abs(fixed_gate[v] * scale - sigma[v])) << v;
    EXPECT_NEAR(noise_gate[v] * scale, sigma[v], 0.25 * sigma[v]) << v;
  }
  EXPECT_LT(fixed_gate[2] * scale, 0.95 * sigma[2]);
}

}  // namespace
}  // namespace sacfuse
