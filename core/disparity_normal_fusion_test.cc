// disparity_normal ([13], fusibile-like): exact planes seen by nadir views shifted by whole pixels, one view
// biased, one view seeing a steep ramp (disparity agrees on the crossing line, normals do not).
#include "core/disparity_normal_fusion.h"

#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/method_test_scene.h"
#include "core/sac_test_scene.h"
#include "tests/support/error_of.h"

namespace sacfuse {
namespace {

using testing::CollectingSink;
using testing::kEast;
using testing::kGroundZ;
using testing::kNorth;
using testing::NadirView;
using testing::PlaneDepth;
using Block = testing::MethodBlock;

constexpr double kHeight = testing::kNadirHeightM;
constexpr double kGsd = testing::kNadirGsdM;
constexpr double kShift = testing::kWholePixelShiftM;

size_t UniqueCells(const std::vector<FusedPoint>& points) { return testing::UniqueGroundCells(points, kGsd); }

TEST(DisparityNormalFusionTest, PointsSeenByTwoMoreViewsAreAveragedOnceAndTheRestDropped) {
  Block block;
  for (uint32_t i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + i * kShift, kNorth, kHeight);
    block.Add(v, PlaneDepth(v), testing::UniformImage(PlaneDepth(v), static_cast<uint8_t>(30 * i), 0, 0));
  }
  CollectingSink sink;
  const FusionStats stats = RunDisparityNormalFusion(block.SacViews(), DisparityNormalOptions{}, sink);
  // Only the 24 columns all three views see have two consistent neighbours: view 0 emits them (averages of
  // three identical points), marking the other views' pixels there as used; nothing else qualifies.
  EXPECT_EQ(stats.emitted_per_view[0], 24u * 90u);
  EXPECT_EQ(stats.emitted_per_view[1], 0u);
  EXPECT_EQ(stats.emitted_per_view[2], 0u);
  EXPECT_EQ(stats.counter("members_averaged"), 2u * 24u * 90u);
  ASSERT_EQ(sink.points().size(), 24u * 90u);
  for (const FusedPoint& p : sink.points()) {
    EXPECT_NEAR(p.point_in_world.z(), kGroundZ, 1e-6);
    EXPECT_EQ(p.view_index, 0u);
    EXPECT_EQ(p.rgb[0], 30);  // mean of 0, 30, 60
  }
  EXPECT_EQ(UniqueCells(sink.points()), sink.points().size());  // no duplicates
}

TEST(DisparityNormalFusionTest, ABiasedViewIsNotAveragedIn) {
  // Views 0 (centre), 1 (+8 m), 2 (-8 m) see the plane; view 3 (+4 m) sees it 20 m too deep: a disparity error of
  // f b (1/500 - 1/520) = 0.92 px against view 0, beyond the 0.5 px threshold.
  Block block;
  const View v0 = NadirView(0, kEast, kNorth, kHeight);
  const View v1 = NadirView(1, kEast + kShift, kNorth, kHeight);
  const View v2 = NadirView(2, kEast - kShift, kNorth, kHeight);
  const View v3 = NadirView(3, kEast + kShift / 2, kNorth, kHeight);
  block.Add(v0, PlaneDepth(v0));
  block.Add(v1, PlaneDepth(v1));
  block.Add(v2, PlaneDepth(v2));
  block.Add(v3, PlaneDepth(v3, 20.0));
  CollectingSink sink;
  const FusionStats stats = RunDisparityNormalFusion(block.SacViews(), DisparityNormalOptions{}, sink);
  EXPECT_EQ(stats.emitted_per_view[0], 24u * 90u);  // columns 48..71 of view 0: views 1 and 2 both agree
  EXPECT_EQ(stats.emitted_per_view[3], 0u);
  for (const FusedPoint& p : sink.points()) EXPECT_NEAR(p.point_in_world.z(), kGroundZ, 1e-6);
  // Three consistent views required: only two agree anywhere, so nothing survives.
  DisparityNormalOptions strict;
  strict.min_consistent_views = 3;
  CollectingSink none;
  EXPECT_EQ(RunDisparityNormalFusion(block.SacViews(), strict, none).emitted, 0u);
}

TEST(DisparityNormalFusionTest, NormalsMustAgreeWhereDisparitiesDo) {
  // Views 0 and 1 see the plane; view 2 sees a 60-degree ramp crossing it along x = kEast + 4 m. Near that line
  // view 2's disparities agree with the plane but its normals are 60 degrees off. With a 0.05 px disparity
  // threshold (the 4 m baselines are short) "near" is |x - x0| < 0.05 z^2 / (f b tan 60) = 0.6 m.
  Block block;
  const View v0 = NadirView(0, kEast, kNorth, kHeight);
  const View v1 = NadirView(1, kEast + kShift, kNorth, kHeight);
  const View v2 = NadirView(2, kEast + kShift / 2, kNorth, kHeight);
  block.Add(v0, PlaneDepth(v0));
  block.Add(v1, PlaneDepth(v1));
  block.Add(v2, testing::TiltedPlaneDepth(v2, kGroundZ, kEast + 4.0, std::tan(60.0 * M_PI / 180.0)));
  DisparityNormalOptions options;
  options.disparity_threshold_px = 0.05;
  CollectingSink sink;
  EXPECT_EQ(RunDisparityNormalFusion(block.SacViews(), options, sink).emitted, 0u);
  DisparityNormalOptions no_normal_test = options;
  no_normal_test.normal_threshold_deg = 90.0;
  CollectingSink line;
  const FusionStats stats = RunDisparityNormalFusion(block.SacViews(), no_normal_test, line);
  EXPECT_GT(stats.emitted, 2u * 90u);   // a strip along the crossing line: 90 rows, ~7 pixels wide
  EXPECT_LT(stats.emitted, 20u * 90u);
  for (const FusedPoint& p : line.points()) EXPECT_NEAR(p.point_in_world.x(), kEast + 4.0, 1.0);
}

TEST(DisparityNormalFusionTest, OptionsAreValidatedWithTheirFields) {
  DisparityNormalOptions o;
  o.disparity_threshold_px = -1;
  o.normal_threshold_deg = 200;
  o.min_consistent_views = 0;
  o.normal_radius_px = 0;
  const std::string what = testing::OptionErrorOf([&] { ValidateDisparityNormalOptions(o); });
  for (const char* key :
       {"DisparityNormalOptions.disparity_threshold_px = -1", "DisparityNormalOptions.normal_threshold_deg = 200",
        "DisparityNormalOptions.min_consistent_views = 0", "DisparityNormalOptions.normal_radius_px = 0"}) {
    EXPECT_NE(what.find(key), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace sacfuse
