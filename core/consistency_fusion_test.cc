// consistency ([15]): hand-made nadir blocks over a plane whose answers are known by construction. Views of
// equal resolution shifted by whole pixels, so a reprojected pixel centre lands on a neighbour's pixel centre.
#include "core/consistency_fusion.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/method_test_scene.h"
#include "core/sac_test_scene.h"
#include "tests/support/error_of.h"

namespace sacfuse {
namespace {

using testing::AllNeighbours;
using testing::CollectingSink;
using testing::kEast;
using testing::kGroundZ;
using testing::kNorth;
using testing::NadirView;
using testing::PlaneDepth;
using Block = testing::MethodBlock;

constexpr double kHeight = 500.0;            // metres above the plane
constexpr double kGsd = kHeight / 3000.0;    // 1/6 m per pixel
constexpr double kShift = 48 * kGsd;         // 8 m: 48 whole pixels

TEST(ConsistencyFusionTest, AgreeingViewsKeepEachSurfacePointOnceFromTheFirstView) {
  Block block;
  for (uint32_t i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + i * kShift, kNorth, kHeight);
    block.Add(v, PlaneDepth(v));
  }
  const auto views = block.SacViews();
  CollectingSink sink;
  const FusionStats stats = RunConsistencyFusion(views, ConsistencyOptions{}, sink, nullptr);
  // Equal heights: equal precision, so views go in index order; view 0 keeps all its 120 x 90 pixels, view 1
  // only its 48 columns east of view 0, view 2 its 48 columns east of view 1.
  EXPECT_EQ(stats.emitted_per_view[0], 120u * 90u);
  EXPECT_EQ(stats.emitted_per_view[1], 48u * 90u);
  EXPECT_EQ(stats.emitted_per_view[2], 48u * 90u);
  EXPECT_EQ(stats.emitted, sink.points().size());
  EXPECT_EQ(stats.input_pixels, 3u * 120u * 90u);
  EXPECT_EQ(stats.counter("skipped_marked"), 3u * 120u * 90u - stats.emitted);
  EXPECT_EQ(stats.counter("occluded_hits"), 0u);
  // No duplicates: every point on the plane, one per ground cell of a pixel.
  std::set<std::pair<long, long>> cells;
  for (const FusedPoint& p : sink.points()) {
    EXPECT_NEAR(p.point_in_world.z(), kGroundZ, 1e-6);
    cells.emplace(std::lround((p.point_in_world.x() - kEast) / kGsd - 0.5),
                  std::lround((p.point_in_world.y() - kNorth) / kGsd - 0.5));
  }
  EXPECT_EQ(cells.size(), sink.points().size());
}

TEST(ConsistencyFusionTest, TheMorePreciseViewIsTheRepresentative) {
  Block block;
  const View high = NadirView(0, kEast, kNorth, kHeight);
  const View low = NadirView(1, kEast, kNorth, kHeight / 2);  // half the GSD, a quarter of z^2/f
  block.Add(high, PlaneDepth(high));
  block.Add(low, PlaneDepth(low));
  const auto views = block.SacViews();
  const ViewPlan plan = ViewPlanFromDepth(views, NeighborViewOptions{});
  ASSERT_EQ(plan.order, (std::vector<uint32_t>{1, 0}));
  CollectingSink sink;
  const FusionStats stats = RunConsistencyFusion(views, ConsistencyOptions{}, sink, &plan);
  EXPECT_EQ(stats.emitted_per_view[1], 120u * 90u);  // all of the low view
  // The high view keeps only what lies outside the low view's footprint (its 30 border columns on each side and
  // 22-23 border rows); its pixels over the low footprint are hit by the finer view's points.
  EXPECT_LT(stats.emitted_per_view[0], 120u * 90u - 55u * 40u);
  EXPECT_GT(stats.emitted_per_view[0], 120u * 90u - 62u * 47u);
}

TEST(ConsistencyFusionTest, OccludedDepthsAreRemovedAndOnlyRelativeAgreementCountsAsRedundant) {
  // View 1's depth lies 3 % behind the plane (an occluded / wrong surface): view 0's points lie in front of it,
  // so its overlapping depths are removed as occluded. View 2's lies 3 % in FRONT of the plane: neither
  // redundant nor occluded by view 0, so both survive (the method's weakness with biased depth maps).
  Block block;
  const View v0 = NadirView(0, kEast, kNorth, kHeight);
  const View v1 = NadirView(1, kEast + kShift, kNorth, kHeight);
  const View v2 = NadirView(2, kEast - kShift, kNorth, kHeight);
  block.Add(v0, PlaneDepth(v0));
  block.Add(v1, PlaneDepth(v1, 0.03 * kHeight));
  block.Add(v2, PlaneDepth(v2, -0.03 * kHeight));
  const auto views = block.SacViews();
  // v1 and v2 do not overlap each other's depths in a way that matters: give each only view 0 as neighbour.
  ViewPlan plan = AllNeighbours(3, {0, 1, 2});
  plan.neighbors[1] = {0};
  plan.neighbors[2] = {0};
  CollectingSink sink;
  const FusionStats stats = RunConsistencyFusion(views, ConsistencyOptions{}, sink, &plan);
  EXPECT_EQ(stats.emitted_per_view[0], 120u * 90u);
  EXPECT_EQ(stats.emitted_per_view[1], 48u * 90u);   // the 72 overlapping columns were occluded
  EXPECT_EQ(stats.emitted_per_view[2], 120u * 90u);  // nothing removed
  EXPECT_EQ(stats.counter("occluded_hits"), 72u * 90u);
  EXPECT_EQ(stats.counter("redundant_hits"), 0u);
  // A 0.5 % bias is within the 1 % threshold: redundant, removed.
  Block near;
  near.Add(v0, PlaneDepth(v0));
  near.Add(v1, PlaneDepth(v1, 0.005 * kHeight));
  CollectingSink sink2;
  const FusionStats s2 = RunConsistencyFusion(near.SacViews(), ConsistencyOptions{}, sink2, nullptr);
  EXPECT_EQ(s2.emitted_per_view[1], 48u * 90u);
  EXPECT_EQ(s2.counter("redundant_hits"), 72u * 90u);
  EXPECT_EQ(s2.counter("occluded_hits"), 0u);
}

TEST(ConsistencyFusionTest, OptionsAreValidatedWithTheirFields) {
  ConsistencyOptions o;
  o.depth_threshold_rel = 0.0;
  const std::string what = testing::OptionErrorOf([&] { ValidateConsistencyOptions(o); });
  EXPECT_NE(what.find("ConsistencyOptions.depth_threshold_rel = 0"), std::string::npos) << what;
  Block block;
  const View v = NadirView(0, kEast, kNorth, kHeight);
  block.Add(v, PlaneDepth(v));
  CollectingSink sink;
  ViewPlan bad;  // no neighbour lists
  EXPECT_THROW(RunConsistencyFusion(block.SacViews(), ConsistencyOptions{}, sink, &bad), Error);
}

}  // namespace
}  // namespace sacfuse
