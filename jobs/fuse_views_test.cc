#include "jobs/fuse_views.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/fusion_methods.h"
#include "core/sac_test_scene.h"
#include "jobs/point_sinks.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::NadirView;
using testing::PlaneDepth;

// Two nadir views over the plane, loaded as the block's views 4 and 7 (as a tile's subset would be).
class FakeSource : public ViewSource {
 public:
  std::unique_ptr<LoadedViews> Load(const FusionNeeds& needs) const override {
    auto out = std::make_unique<LoadedViews>();
    out->Reserve(2);
    const View views[2] = {NadirView(4, kEast - 10.0, testing::kNorth, 300.0),
                           NadirView(7, kEast + 10.0, testing::kNorth, 300.0)};
    for (size_t i = 0; i < 2; ++i) {
      out->depths[i] = PlaneDepth(views[i]);
      PixelWindow whole;
      whole.row_end = out->depths[i].height;
      whole.col_end = out->depths[i].width;
      if (!needs.colours_one_view_at_a_time) out->colours[i] = LoadColours(*out, i);
      out->AddView(views[i].index, views[i], {out->depths[i].width, out->depths[i].height}, whole, needs, i);
    }
    return out;
  }
  // One colour per view: (100 + i, 50, 25) on a 2 x 2 image.
  RgbImage LoadColours(const LoadedViews&, size_t i) const override {
    RgbImage image(2, 2, 3, 0);
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) {
        image.at(r, c, 0) = static_cast<uint8_t>(100 + i);
        image.at(r, c, 1) = 50;
        image.at(r, c, 2) = 25;
      }
    }
    return image;
  }
};

class VectorSink : public PointSink {
 public:
  void Write(const FusedPoint* p, size_t n) override { points.insert(points.end(), p, p + n); }
  std::vector<FusedPoint> points;
};

// Emits every valid pixel whatever the scope says, and records what it was given.
class EverythingMethod : public FusionMethod {
 public:
  explicit EverythingMethod(FusionNeeds needs) : needs_(needs) {}
  std::string name() const override { return "everything"; }
  FusionNeeds needs() const override { return needs_; }
  FusionStats Fuse(const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) const override {
    plan_size = scope.plan != nullptr ? scope.plan->neighbors.size() : 0;
    gsd_m = scope.gsd_m;
    images_held = 0;
    for (const SacView& v : views) images_held += v.image != nullptr ? 1 : 0;
    if (scope.colours != nullptr) second_view_red = scope.colours->Load(1).at(1, 1, 0);
    return MakeUnionMethod()->Fuse(views, scope, sink);
  }
  mutable size_t plan_size = 0;
  mutable double gsd_m = 0.0;
  mutable size_t images_held = 0;
  mutable int second_view_red = -1;  // of scope.colours->Load(1); -1 = no scope.colours

 private:
  FusionNeeds needs_;
};

OwnedRegion WestHalf() {
  OwnedRegion west;
  west.max.x() = kEast;
  return west;
}
const OwnedRegion kWestHalf = WestHalf();

TEST(FuseViewsTest, KeepsTheOwnedPointsOfMethodsThatDoNotJudgePixels) {
  VectorSink sink;
  FusionScope scope;
  scope.owns = kWestHalf;
  const FusedViews out = FuseViews(*MakeUnionMethod(), FakeSource(), nullptr, scope, sink);
  ASSERT_FALSE(sink.points.empty());
  for (const FusedPoint& p : sink.points) EXPECT_LT(p.point_in_world.x(), kEast);
  EXPECT_EQ(out.points_written, sink.points.size());
  EXPECT_GT(out.points_not_owned, 0u);
  // Input counts only the owned pixels: for the union they are exactly the points written.
  EXPECT_EQ(out.stats.input_pixels, out.points_written);
  EXPECT_EQ(out.stats.input_pixels + out.points_not_owned, 2u * 120 * 90);
  EXPECT_EQ(out.view_ids, (std::vector<uint32_t>{4, 7}));
  EXPECT_GT(out.stats.input_per_view[0], out.stats.input_per_view[1]);  // view 4 lies further west
}

TEST(FuseViewsTest, LeavesOwnershipToMethodsThatJudgePixelsThemselves) {
  FusionNeeds needs;
  needs.owns_pixels = true;
  VectorSink sink;
  FusionScope scope;
  scope.owns = kWestHalf;
  const FusedViews out = FuseViews(EverythingMethod(needs), FakeSource(), nullptr, scope, sink);
  EXPECT_EQ(sink.points.size(), 2u * 120 * 90);  // this method ignored the owner, and FuseViews did not filter
  EXPECT_LT(out.stats.input_pixels, 2u * 120 * 90);
}

TEST(FuseViewsTest, ColoursComeWithTheViewsOrOneViewAtATimeAsTheMethodNeeds) {
  VectorSink sink;
  EverythingMethod with_views{FusionNeeds{}};
  FuseViews(with_views, FakeSource(), nullptr, FusionScope{}, sink);
  EXPECT_EQ(with_views.images_held, 2u);
  EXPECT_EQ(with_views.second_view_red, -1);
  ASSERT_FALSE(sink.points.empty());
  EXPECT_EQ(sink.points.back().rgb, (std::array<uint8_t, 3>{101, 50, 25}));

  FusionNeeds needs;
  needs.colours_one_view_at_a_time = true;
  EverythingMethod on_demand(needs);
  FuseViews(on_demand, FakeSource(), nullptr, FusionScope{}, sink);
  EXPECT_EQ(on_demand.images_held, 0u);
  EXPECT_EQ(on_demand.second_view_red, 101);
}

TEST(FuseViewsTest, WithoutAnOwnerEveryPixelCounts) {
  VectorSink sink;
  const FusedViews out = FuseViews(*MakeUnionMethod(), FakeSource(), nullptr, FusionScope{}, sink);
  EXPECT_EQ(out.stats.input_pixels, 2u * 120 * 90);
  EXPECT_EQ(out.points_written, 2u * 120 * 90);
  EXPECT_EQ(out.points_not_owned, 0u);
}

TEST(FuseViewsTest, GivesBlockGeometryMethodsTheBlockPlanRestrictedToTheLoadedViews) {
  FusionNeeds needs;
  needs.block_geometry = true;
  EverythingMethod method(needs);
  MethodGeometry geometry;
  geometry.gsd_m = 0.1;
  geometry.plan.neighbors.resize(10);
  for (uint32_t v = 0; v < 10; ++v) {
    geometry.plan.order.push_back(v);
    for (uint32_t n = 0; n < 10; ++n) {
      if (n != v) geometry.plan.neighbors[v].push_back(n);
    }
  }
  VectorSink sink;
  FuseViews(method, FakeSource(), &geometry, FusionScope{}, sink);
  EXPECT_EQ(method.plan_size, 2u);
  EXPECT_DOUBLE_EQ(method.gsd_m, 0.1);
  EXPECT_THROW(FuseViews(method, FakeSource(), nullptr, FusionScope{}, sink), Error);
}

TEST(PointSinksTest, CountingSinkCountsPerSourceView) {
  VectorSink end;
  CountingSink counting(end);
  FusedPoint p[3];
  p[0].view_index = 2;
  p[1].view_index = 2;
  p[2].view_index = 0;
  counting.Write(p, 3);
  EXPECT_EQ(counting.count(), 3u);
  EXPECT_EQ(counting.per_view(), (std::vector<uint64_t>{1, 0, 2}));  // view 9 and others beyond: none
  EXPECT_EQ(end.points.size(), 3u);
}

}  // namespace
}  // namespace sacfuse
