#include "core/combine_anchors.h"

#include <cmath>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "core/method_test_scene.h"
#include "core/sac_fusion.h"
#include "core/sac_test_scene.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::kGroundZ;
using testing::kNadirGsdM;
using testing::kNadirHeightM;
using testing::kNorth;
using testing::NadirView;

// One nadir view (GSD kNadirGsdM = 0.167 m) over the plane z = ground + slope (x - east), and the exact depth of
// that plane on the ray of any of its pixels.
struct OneViewOverAPlane {
  double slope;
  testing::MethodBlock block;
  std::vector<SacView> views;
  explicit OneViewOverAPlane(double plane_slope) : slope(plane_slope) {
    const View v = NadirView(0, kEast, kNorth, kNadirHeightM);
    block.Add(v, testing::TiltedPlaneDepth(v, kGroundZ, kEast, slope));
    views = block.SacViews();
  }
  double PlaneDepthAt(int row, int col) const {
    const SacView& v = views[0];
    const Eigen::Vector3d c = v.world_from_cam.translation;
    const Eigen::Vector3d ray = v.world_from_cam.rotation * v.depth_camera.Unproject(col + 0.5, row + 0.5, 1.0);
    return (kGroundZ - c.z() + slope * (c.x() - kEast)) / (ray.z() - slope * ray.x());
  }
  // The plane's normal in the world (upward).
  Eigen::Vector3d Normal() const { return Eigen::Vector3d(-slope, 0.0, 1.0).normalized(); }
  // The exact combine of pixel (row, col) as CombineDepth would leave it: the other depth maps at the plane with
  // summed weight `weight`.
  CombinedDepth Exact(int row, int col, double weight) const {
    CombinedDepth c;
    c.others_depth_m = PlaneDepthAt(row, col);
    c.others_weight = weight;
    c.support = 3;
    return c;
  }
};

const PixelWindow kPatch{10, 42, 20, 84};  // rows 10-41, cols 20-83

TEST(CombineAnchorsTest, AnchorsAreEverySecondRowAndColumnFromThePatchsFirstPixel) {
  const CombineAnchors anchors(kPatch);
  EXPECT_TRUE(anchors.IsAnchor(10, 20));
  EXPECT_TRUE(anchors.IsAnchor(12, 22));
  EXPECT_FALSE(anchors.IsAnchor(11, 20));
  EXPECT_FALSE(anchors.IsAnchor(10, 21));
  EXPECT_FALSE(anchors.IsAnchor(11, 21));
  const CombineAnchors odd({11, 40, 21, 60});
  EXPECT_TRUE(odd.IsAnchor(11, 21));
  EXPECT_FALSE(odd.IsAnchor(12, 22));
}

TEST(CombineAnchorsTest, CarriesTheAnchorsSurfaceAlongThePlaneOntoThePixelsRay) {
  // A 45 degree roof: the depth changes by ~1 GSD per pixel, so the anchors two pixels apart differ by ~2 GSDs
  // (more than the 1 GSD tolerance) as depths, but carried along the plane they meet on the pixel's ray.
  const OneViewOverAPlane s(1.0);
  CombineAnchors anchors(kPatch);
  for (const auto& [r, c] : {std::pair{20, 30}, {20, 32}, {22, 30}, {22, 32}}) anchors.Set(r, c, s.Exact(r, c, 3.0));
  const double truth = s.PlaneDepthAt(21, 31);
  ASSERT_GT(std::abs(s.PlaneDepthAt(20, 30) - s.PlaneDepthAt(22, 32)), 1.5 * kNadirGsdM);
  DepthCombineOptions options;
  options.gate_gsd = 4.0;
  double combined = 0.0;
  // Own depth 0.2 m long, weight 1 against the others' 3: (d + 3 M) / 4.
  ASSERT_TRUE(anchors.Interpolate(s.views, 0, 21, 31, truth + 0.2, {}, options, s.Normal(), &combined));
  EXPECT_NEAR(combined, truth + 0.05, 1e-6);
  // Between two anchors of its row, or of its column.
  ASSERT_TRUE(anchors.Interpolate(s.views, 0, 20, 31, s.PlaneDepthAt(20, 31), {}, options, s.Normal(), &combined));
  EXPECT_NEAR(combined, s.PlaneDepthAt(20, 31), 1e-6);
  ASSERT_TRUE(anchors.Interpolate(s.views, 0, 21, 30, s.PlaneDepthAt(21, 30), {}, options, s.Normal(), &combined));
  EXPECT_NEAR(combined, s.PlaneDepthAt(21, 30), 1e-6);
  // Without the plane the anchors' depths are compared as they are: 2 GSDs apart, so no interpolation.
  EXPECT_FALSE(anchors.Interpolate(s.views, 0, 21, 31, truth, {}, options, Eigen::Vector3d::Zero(), &combined));
  // On a gentle slope the depths alone agree within the tolerance: their mean.
  const OneViewOverAPlane gentle(0.1);
  CombineAnchors flat(kPatch);
  for (const auto& [r, c] : {std::pair{20, 30}, {22, 32}}) flat.Set(r, c, gentle.Exact(r, c, 1.0));
  ASSERT_TRUE(flat.Interpolate(gentle.views, 0, 21, 31, gentle.PlaneDepthAt(21, 31), {}, options,
                               Eigen::Vector3d::Zero(), &combined));
  EXPECT_NEAR(combined, gentle.PlaneDepthAt(21, 31), 1e-3);
}

TEST(CombineAnchorsTest, CombinesExactlyWhereTheNeighboursDoNotVouchForASmoothSurface) {
  const OneViewOverAPlane s(0.3);
  DepthCombineOptions options;
  options.gate_gsd = 4.0;  // 0.67 m
  const Eigen::Vector3d n = s.Normal();
  double combined = 0.0;
  const double truth = s.PlaneDepthAt(21, 31);
  {  // One exactly combined neighbour is not enough; an anchor where nothing agreed does not count.
    CombineAnchors anchors(kPatch);
    anchors.Set(20, 30, s.Exact(20, 30, 2.0));
    EXPECT_FALSE(anchors.Interpolate(s.views, 0, 21, 31, truth, {}, options, n, &combined));
    anchors.Set(22, 32, CombinedDepth{});  // others_weight 0: the own depth alone
    EXPECT_FALSE(anchors.Interpolate(s.views, 0, 21, 31, truth, {}, options, n, &combined));
    anchors.Set(22, 30, s.Exact(22, 30, 2.0));
    EXPECT_TRUE(anchors.Interpolate(s.views, 0, 21, 31, truth, {}, options, n, &combined));
  }
  {  // A step: two neighbours 0.5 m (3 GSDs) deeper than the plane.
    CombineAnchors anchors(kPatch);
    anchors.Set(20, 30, s.Exact(20, 30, 2.0));
    anchors.Set(20, 32, s.Exact(20, 32, 2.0));
    CombinedDepth low = s.Exact(22, 30, 2.0);
    low.others_depth_m += 0.5;
    anchors.Set(22, 30, low);
    low = s.Exact(22, 32, 2.0);
    low.others_depth_m += 0.5;
    anchors.Set(22, 32, low);
    EXPECT_FALSE(anchors.Interpolate(s.views, 0, 21, 31, truth, {}, options, n, &combined));
    // A step within the tolerance (0.1 m < 1 GSD) interpolates.
    anchors.Set(22, 30, s.Exact(22, 30, 2.0));
    low = s.Exact(22, 32, 2.0);
    low.others_depth_m += 0.1;
    anchors.Set(22, 32, low);
    EXPECT_TRUE(anchors.Interpolate(s.views, 0, 21, 31, truth, {}, options, n, &combined));
    // The own depth outside the gate of the others' surface: exact (the combine would drop them all).
    EXPECT_FALSE(anchors.Interpolate(s.views, 0, 21, 31, truth + 1.0, {}, options, n, &combined));
  }
  {  // Neighbours outside the patch are not read: the patch's last row has no anchors below it.
    CombineAnchors anchors(kPatch);
    anchors.Set(40, 30, s.Exact(40, 30, 2.0));
    EXPECT_FALSE(anchors.Interpolate(s.views, 0, 41, 31, s.PlaneDepthAt(41, 31), {}, options, n, &combined));
    anchors.Set(40, 32, s.Exact(40, 32, 2.0));
    EXPECT_TRUE(anchors.Interpolate(s.views, 0, 41, 31, s.PlaneDepthAt(41, 31), {}, options, n, &combined));
  }
}

// Four noisy nadir views of a tilted plane fused with and without anchors: the same points, about half of them
// interpolated, as close to the plane as the exact combine's, and each within a few centimetres of it.
TEST(CombineAnchorsTest, FusionWithAnchorsKeepsThePointsAndTheirAccuracy) {
  constexpr double kSlope = 0.3;
  testing::SyntheticBlock block;
  std::mt19937 rng(11);
  const double shifts[4][2] = {{0.0, 0.0}, {8.0, 0.0}, {0.0, -5.0}, {8.0, -5.0}};
  for (uint32_t i = 0; i < 4; ++i) {
    const View v = NadirView(i, kEast + shifts[i][0], kNorth + shifts[i][1], kNadirHeightM);
    DepthMap depth = testing::TiltedPlaneDepth(v, kGroundZ, kEast, kSlope);
    testing::AddDepthNoise(&depth, 0.05, &rng);
    block.Add(v, depth);
  }
  const std::vector<SacView> views = block.SacViews();
  SacOptions options;
  options.superpixels.region_size_px = 6;
  options.min_consistent_views = 1;
  auto fuse = [&](bool anchors, SacStats* stats) {
    options.combine_anchors = anchors;
    testing::CollectingSink sink;
    *stats = RunSacFusion(views, options, sink);
    return sink.points();
  };
  SacStats with_stats, exact_stats;
  const std::vector<FusedPoint> with = fuse(true, &with_stats);
  const std::vector<FusedPoint> exact = fuse(false, &exact_stats);
  ASSERT_EQ(with.size(), exact.size());
  ASSERT_GT(with.size(), 10000u);
  EXPECT_EQ(exact_stats.collapse.interpolated, 0u);
  EXPECT_GT(with_stats.collapse.interpolated, with.size() / 3);
  auto residual = [&](const FusedPoint& p) {
    return p.point_in_world.z() - (kGroundZ + kSlope * (p.point_in_world.x() - kEast));
  };
  double sq_with = 0.0, sq_exact = 0.0, max_apart = 0.0;
  for (size_t i = 0; i < with.size(); ++i) {
    ASSERT_EQ(with[i].view_index, exact[i].view_index);
    sq_with += residual(with[i]) * residual(with[i]);
    sq_exact += residual(exact[i]) * residual(exact[i]);
    max_apart = std::max(max_apart, (with[i].point_in_world - exact[i].point_in_world).norm());
  }
  const double rms_with = std::sqrt(sq_with / with.size()), rms_exact = std::sqrt(sq_exact / exact.size());
  EXPECT_LT(rms_with, 1.05 * rms_exact) << rms_with << " against " << rms_exact;
  // The interpolated surface differs from the exact one by at most the anchors' tolerance (1 GSD) plus the noise
  // of the few depth maps behind each.
  EXPECT_LT(max_apart, kAnchorToleranceGsd * kNadirGsdM) << "a point moved farther than the tolerance allows";
  std::cout << "rms to the plane: " << rms_with << " m with anchors, " << rms_exact << " m exact; max apart "
            << max_apart << " m; " << with_stats.collapse.interpolated << " of " << with.size() << " interpolated\n";
}

}  // namespace
}  // namespace sacfuse
