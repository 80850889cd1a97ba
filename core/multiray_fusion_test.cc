// multiray ([35]): per-pixel correspondence groups triangulated from their rays, on exact planes seen by nadir
// views shifted by whole pixels (every member's pixel centre sees the reference's ground point).
#include "core/multiray_fusion.h"

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

TEST(MultirayFusionTest, EachSurfacePointIsTriangulatedOnceFromAllItsRays) {
  Block block;
  for (uint32_t i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + i * kShift, kNorth, kHeight);
    block.Add(v, PlaneDepth(v));
  }
  CollectingSink sink;
  const FusionStats stats = RunMultirayFusion(block.SacViews(), MultirayOptions{}, sink);
  // View 0 seeds a group wherever another view sees its pixel (its 72 eastern columns); view 1 then seeds its 48
  // columns east of view 0, which view 2 sees; view 2's remaining 48 columns have a single ray: dropped.
  EXPECT_EQ(stats.emitted_per_view[0], 72u * 90u);
  EXPECT_EQ(stats.emitted_per_view[1], 48u * 90u);
  EXPECT_EQ(stats.emitted_per_view[2], 0u);
  EXPECT_EQ(stats.counter("too_few_rays"), 48u * 90u + 48u * 90u);  // view 0's west, view 2's east columns
  // 24 columns have three rays, the other 96 two.
  EXPECT_EQ(stats.counter("rays_triangulated"), 24u * 90u * 3u + 96u * 90u * 2u);
  for (const FusedPoint& p : sink.points()) EXPECT_NEAR(p.point_in_world.z(), kGroundZ, 1e-6);
  EXPECT_EQ(UniqueCells(sink.points()), sink.points().size());
}

TEST(MultirayFusionTest, BiasedDepthsAreNoMembersAndPureRaysIgnoreDepth) {
  // View 1 sees the plane 2 m too deep: beyond 3 local GSDs (0.5 m), so it joins no group and its own groups
  // find no partner.
  Block block;
  const View v0 = NadirView(0, kEast, kNorth, kHeight);
  const View v1 = NadirView(1, kEast + kShift, kNorth, kHeight);
  const View v2 = NadirView(2, kEast + 2 * kShift, kNorth, kHeight);
  block.Add(v0, PlaneDepth(v0));
  block.Add(v1, PlaneDepth(v1, 2.0));
  block.Add(v2, PlaneDepth(v2));
  CollectingSink sink;
  const FusionStats stats = RunMultirayFusion(block.SacViews(), MultirayOptions{}, sink);
  EXPECT_EQ(stats.emitted_per_view[0], 24u * 90u);  // the columns view 2 also sees
  EXPECT_EQ(stats.emitted_per_view[1], 0u);
  for (const FusedPoint& p : sink.points()) EXPECT_NEAR(p.point_in_world.z(), kGroundZ, 1e-6);
  // A 0.3 m bias is within tolerance: view 1 joins. Its ray passes through the true ground point (pixel
  // geometry does not depend on depth), so the pure ray intersection ignores its depth and lands on the plane;
  // with depth terms the point moves toward view 1's measurement, along the nearly vertical rays.
  Block near;
  near.Add(v0, PlaneDepth(v0));
  near.Add(v1, PlaneDepth(v1, 0.3));
  MultirayOptions rays_only;
  rays_only.depth_sigma_gsd = 0.0;
  CollectingSink pure;
  RunMultirayFusion(near.SacViews(), rays_only, pure);
  ASSERT_EQ(pure.points().size(), 72u * 90u);
  for (const FusedPoint& p : pure.points()) EXPECT_NEAR(p.point_in_world.z(), kGroundZ, 1e-3);
  CollectingSink with_depth;
  RunMultirayFusion(near.SacViews(), MultirayOptions{}, with_depth);
  ASSERT_EQ(with_depth.points().size(), 72u * 90u);
  for (const FusedPoint& p : with_depth.points()) {
    EXPECT_LT(p.point_in_world.z(), kGroundZ - 0.01);
    EXPECT_GT(p.point_in_world.z(), kGroundZ - 0.3);
  }
}

TEST(MultirayFusionTest, OptionsAreValidatedWithTheirFields) {
  MultirayOptions o;
  o.min_rays = 1;
  o.depth_sigma_gsd = -1;
  const std::string what = testing::OptionErrorOf([&] { ValidateMultirayOptions(o); });
  EXPECT_NE(what.find("MultirayOptions.min_rays = 1"), std::string::npos) << what;
  EXPECT_NE(what.find("MultirayOptions.depth_sigma_gsd = -1"), std::string::npos) << what;
}

}  // namespace
}  // namespace sacfuse
