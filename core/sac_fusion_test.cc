// SAC on synthetic blocks whose answers are known by construction (see sac_test_scene.h).
#include "core/sac_fusion.h"

#include <mutex>
#include <set>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/backproject.h"
#include "core/error.h"
#include "core/sac_test_scene.h"

namespace sacfuse {
namespace {

using testing::CollectingSink;
using testing::kEast;
using testing::kGroundZ;
using testing::kNorth;
using testing::NadirView;
using testing::PlaneDepth;
using testing::SyntheticBlock;

SacOptions TestOptions() {
  SacOptions o;
  o.superpixels.region_size_px = 6;
  o.min_consistent_views = 1;
  return o;
}

// Depth pixel -> world -> the same pixel and depth, with UTM-sized coordinates (no float precision loss).
TEST(SacGeometryTest, BackprojectionAndReprojectionRoundTripAtUtmCoordinates) {
  const View view = NadirView(0, kEast + 12.34, kNorth + 56.78, 500.0);
  const DepthMap depth = PlaneDepth(view);
  SuperpixelMap spx = testing::GridSuperpixels(depth, 6);
  const SacView sac = MakeSacView(view, &depth, &spx, nullptr);
  for (const auto& [row, col] : std::vector<std::pair<int, int>>{{0, 0}, {45, 60}, {89, 119}, {10, 100}}) {
    const Eigen::Vector3d p = DepthPixelToWorld(sac.depth_camera, sac.world_from_cam, col, row, depth.at(row, col));
    EXPECT_NEAR(p.z(), kGroundZ, 1e-6);  // on the plane to a micrometre even at northing 5.7e6
    const DepthLookup back = LookupDepth(sac, p);
    ASSERT_TRUE(back.inside);
    EXPECT_EQ(back.row, row);
    EXPECT_EQ(back.col, col);
    EXPECT_NEAR(back.z_m, depth.at(row, col), 1e-4);
  }
  // The nadir pixel under the camera centre: ground point straight below.
  const Eigen::Vector3d centre = DepthPixelToWorld(sac.depth_camera, sac.world_from_cam, 59, 44, 500.0);
  EXPECT_NEAR(centre.x(), kEast + 12.34 - 0.5 * 500.0 / 3000.0, 1e-6);  // pixel centre 59.5 is 0.5 px west
  EXPECT_NEAR(centre.y(), kNorth + 56.78 + 0.5 * 500.0 / 3000.0, 1e-6);
}

// Two views of one plane: view 0 flies at half the height (GSD 8 cm vs 17 cm). The quality unary must select
// view 0 wherever it sees the plane; view 1 keeps exactly the ground view 0 does not cover (coverage), plus at
// most a few superpixels at the footprint border.
TEST(SacFusionTest, TwoViewsQualityUnarySelectsTheFinerViewAndKeepsCoverage) {
  SyntheticBlock block;
  block.Add(NadirView(0, kEast, kNorth, 250.0), PlaneDepth(NadirView(0, kEast, kNorth, 250.0)));
  block.Add(NadirView(1, kEast + 8.0, kNorth, 500.0), PlaneDepth(NadirView(1, kEast + 8.0, kNorth, 500.0)));
  const auto views = block.SacViews();
  CollectingSink sink;
  const SacStats stats = RunSacFusion(views, TestOptions(), sink);

  // View 0 emits every valid pixel: it is selected everywhere it has data.
  EXPECT_EQ(stats.emitted_per_view[0], views[0].depth->num_pixels());
  // View 1: its pixels over view 0's footprint collapse, the rest are kept.
  const double half_width_0 = 60 * 250.0 / 3000.0, half_height_0 = 45 * 250.0 / 3000.0;
  size_t outside = 0;
  for (int r = 0; r < 90; ++r) {
    for (int c = 0; c < 120; ++c) {
      const Eigen::Vector3d p = DepthPixelToWorld(views[1].depth_camera, views[1].world_from_cam, c, r,
                                                  views[1].depth->at(r, c));
      if (std::abs(p.x() - kEast) > half_width_0 || std::abs(p.y() - kNorth) > half_height_0) ++outside;
    }
  }
  EXPECT_GE(stats.emitted_per_view[1], outside) << "coverage lost";
  EXPECT_LE(stats.emitted_per_view[1], outside + 4 * 6 * 90) << "too little collapsed";
  // Dropped in favour of view 0: counted as redundant (the better view is asked first), or as collapsed by the
  // Netlet chain where view 0 is not the more precise view.
  EXPECT_GT(stats.collapse.redundant, 0u);
  EXPECT_EQ(stats.collapse.collapsed + stats.collapse.redundant + stats.collapse.emitted + stats.collapse.outliers +
                stats.collapse.free_space,
            stats.collapse.input_pixels);
  EXPECT_EQ(stats.collapse.emitted, sink.points().size());
}

// collapse: none keeps every view's pixels that pass their own tests: both views of a plane emit every pixel, none is
// dropped for the other view, and no Netlet is labelled (nothing asks for a label). The own tests still hold: with
// two agreeing views needed, view 1's pixels that view 0 does not see are outliers.
TEST(SacFusionTest, CollapseNoneKeepsEveryViewsPixelsThatPassTheirOwnTests) {
  SyntheticBlock block;
  block.Add(NadirView(0, kEast, kNorth, 250.0), PlaneDepth(NadirView(0, kEast, kNorth, 250.0)));
  block.Add(NadirView(1, kEast + 8.0, kNorth, 500.0), PlaneDepth(NadirView(1, kEast + 8.0, kNorth, 500.0)));
  const auto views = block.SacViews();
  SacOptions options = TestOptions();
  options.collapse = "none";
  CollectingSink sink;
  const SacStats stats = RunSacFusion(views, options, sink);
  EXPECT_EQ(stats.emitted_per_view[0], views[0].depth->num_pixels());
  EXPECT_EQ(stats.emitted_per_view[1], views[1].depth->num_pixels());
  EXPECT_EQ(stats.collapse.redundant, 0u);
  EXPECT_EQ(stats.collapse.collapsed, 0u);
  EXPECT_EQ(stats.collapse.kept_uncovered, 0u);
  EXPECT_EQ(stats.labeling.labelled_nodes, 0u);
  EXPECT_EQ(sink.points().size(), views[0].depth->num_pixels() + views[1].depth->num_pixels());

  // With two agreeing views needed, a pixel is kept exactly where the other view sees its ground too (view 1 sees
  // 4x view 0's ground area, 8 m to the east).
  options.min_consistent_views = 2;
  CollectingSink strict_sink;
  const SacStats strict = RunSacFusion(views, options, strict_sink);
  auto seen_by_other = [&](int v) {
    const SacView& own = views[v];
    const SacView& other = views[1 - v];
    uint64_t seen = 0;
    for (int r = 0; r < own.depth->height; ++r) {
      for (int c = 0; c < own.depth->width; ++c) {
        const Eigen::Vector3d p = DepthPixelToWorld(own.depth_camera, own.world_from_cam, c, r, own.depth->at(r, c));
        if (LookupDepth(other, p).inside) ++seen;
      }
    }
    return seen;
  };
  // 70 % of view 0 (its western 3 m of 10 m lie outside view 1), 42 x 45 pixels of view 1.
  EXPECT_EQ(seen_by_other(0), 7560u);
  EXPECT_EQ(seen_by_other(1), 1890u);
  EXPECT_EQ(strict.emitted_per_view[0], 7560u);
  EXPECT_EQ(strict.emitted_per_view[1], 1890u);
  EXPECT_EQ(strict.collapse.redundant + strict.collapse.collapsed + strict.collapse.kept_uncovered, 0u);
  EXPECT_EQ(strict.collapse.outliers, 2u * 120u * 90u - 7560u - 1890u);
}

// Three equal views; view 1's depth map is biased by +0.6 m. Views 0 and 2 agree with each other, view 1 with
// nobody: the Netlets must select a consistent view, so no point of the biased surface survives where the others
// see. (The averaging combine weighs view 1 by its estimated noise factor, which its bias makes large.)
TEST(SacFusionTest, ThreeViewsBiasedViewIsNotSelected) {
  SyntheticBlock block;
  for (int i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + 2.0 * i, kNorth, 500.0);
    block.Add(v, PlaneDepth(v, i == 1 ? 0.6 : 0.0));
  }
  const auto views = block.SacViews();
  SacOptions options = TestOptions();
  options.depth_tolerance_gsd = 5.0;      // 0.83 m: the biased view (3.6 GSD off) still corresponds...
  options.agreement_tolerance_gsd = 1.5;  // ...but does not agree (0.25 m)
  CollectingSink sink;
  const SacStats stats = RunSacFusion(views, options, sink);
  size_t biased_points = 0;
  for (const auto& p : sink.points()) {
    if (std::abs(p.point_in_world.z() - kGroundZ) > 0.3) ++biased_points;
  }
  // Views 0 and 2 together see all of view 1's ground: nothing biased may survive but superpixel borders.
  EXPECT_LT(biased_points, 120u * 90u / 20) << "biased points kept: " << biased_points;
  EXPECT_LT(stats.emitted_per_view[1], stats.emitted_per_view[0] / 4);
  // The labels are solved on demand (core/sac_labeling.h): view 1's pixels are dropped as redundant before their
  // own clusters' labels are asked for, so fewer nodes are labelled than exist (which view 1's Netlets choose is
  // core/sac_labeling_test.cc's ThreeViewNetletsAvoidTheBiasedViewAndBreakTiesByIndex).
  EXPECT_GT(stats.labeling.labelled_nodes, 0u);
  EXPECT_LT(stats.labeling.labelled_nodes, stats.valid_nodes) << stats.labeling.labelled_nodes;
}

// The paper's constant unary: every Netlet takes a single label (its seed's view); still no averaging.
TEST(SacFusionTest, PaperUnaryCollapsesEachNetletOntoOneView) {
  SyntheticBlock block;
  for (int i = 0; i < 2; ++i) {
    const View v = NadirView(i, kEast + 3.0 * i, kNorth, 500.0);
    block.Add(v, PlaneDepth(v));
  }
  SacOptions options = TestOptions();
  options.unary = "paper";
  CollectingSink sink;
  const SacStats stats = RunSacFusion(block.SacViews(), options, sink);
  const uint64_t union_points = 2u * 120u * 90u;
  // Nearly all overlap is collapsed: far fewer points than the union, but more than one view's worth.
  EXPECT_LT(stats.collapse.emitted, union_points * 6 / 10);
  EXPECT_GE(stats.collapse.emitted, 120u * 90u);
}

// Outliers: a view seen by nobody else is removed when min_consistent_views = 2.
TEST(SacFusionTest, UnsupportedPointsAreRemoved) {
  SyntheticBlock block;
  const View a = NadirView(0, kEast, kNorth, 500.0);
  const View b = NadirView(1, kEast + 2.0, kNorth, 500.0);
  block.Add(a, PlaneDepth(a));
  block.Add(b, PlaneDepth(b, 5.0));  // 5 m = 30 GSD off: agrees with nothing
  SacOptions options = TestOptions();
  options.min_consistent_views = 2;
  CollectingSink sink;
  const SacStats stats = RunSacFusion(block.SacViews(), options, sink);
  EXPECT_EQ(stats.collapse.emitted, 0u);
  EXPECT_EQ(stats.collapse.outliers, stats.collapse.input_pixels);
}

// The collapse visits pixels in patches (core/patch_grid.h) but writes each view's points in row order: one view
// wider and taller than a patch, every pixel emitted, each point back at its own pixel.
TEST(SacFusionTest, PointsOfAViewAreWrittenInRowOrder) {
  SyntheticBlock block;
  const View a = NadirView(0, kEast, kNorth, 500.0, 150, 100);
  block.Add(a, PlaneDepth(a));
  CollectingSink sink;
  const auto views = block.SacViews();
  RunSacFusion(views, TestOptions(), sink);
  ASSERT_EQ(sink.points().size(), 150u * 100u);
  for (size_t i = 0; i < sink.points().size(); ++i) {
    const DepthLookup hit = LookupDepth(views[0], sink.points()[i].point_in_world);
    ASSERT_TRUE(hit.inside);
    ASSERT_EQ(hit.row * 150 + hit.col, static_cast<int>(i)) << "point " << i;
  }
}

// Same output, point for point, for 1 and 2 threads (all correspondence strategies that need no input graphs).
TEST(SacFusionTest, DeterministicAcrossThreadCounts) {
  SyntheticBlock block;
  for (int i = 0; i < 4; ++i) {
    const View v = NadirView(i, kEast + 5.0 * (i % 2), kNorth + 4.0 * (i / 2), 400.0 + 20 * i);
    block.Add(v, PlaneDepth(v, 0.05 * i));
  }
  for (const std::string strategy : {"reprojection", "proximity"}) {
    SacOptions options = TestOptions();
    options.correspondence = strategy;
    options.min_consistent_views = 2;
    std::vector<std::vector<FusedPoint>> runs;
    for (int threads : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      CollectingSink sink;
      RunSacFusion(block.SacViews(), options, sink);
      runs.push_back(sink.points());
    }
    ASSERT_EQ(runs[0].size(), runs[1].size()) << strategy;
    ASSERT_GT(runs[0].size(), 0u);
    for (size_t i = 0; i < runs[0].size(); ++i) {
      ASSERT_EQ(runs[0][i].point_in_world, runs[1][i].point_in_world) << strategy << " point " << i;
      ASSERT_EQ(runs[0][i].view_index, runs[1][i].view_index);
    }
  }
}

// Colours given one view at a time (FusionNeeds::colours_one_view_at_a_time): each point has its own view's
// colour, every view's colours are asked once, in order; a loading error reaches the caller.
class SolidColours : public ViewColours {
 public:
  RgbImage Load(size_t i) const override {
    std::lock_guard<std::mutex> lock(mutex_);
    asked_.push_back(i);
    if (i == fail_at_) throw InputError("view " + std::to_string(i) + ".jpg", "cannot decode");
    return RgbImage(3, 2, 3, static_cast<uint8_t>(10 + 20 * i));
  }
  std::vector<size_t> asked() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return asked_;
  }
  size_t fail_at_ = ~size_t{0};

 private:
  mutable std::mutex mutex_;
  mutable std::vector<size_t> asked_;
};

TEST(SacFusionTest, ColoursLoadedOneViewAtATimeColourThatViewsPoints) {
  SyntheticBlock block;
  for (int i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + 6.0 * i, kNorth, 500.0);
    block.Add(v, PlaneDepth(v));
  }
  const auto views = block.SacViews();
  SolidColours colours;
  CollectingSink sink;
  RunSacFusion(views, TestOptions(), sink, {}, {}, &colours);
  ASSERT_FALSE(sink.points().empty());
  std::set<uint32_t> seen;
  for (const FusedPoint& p : sink.points()) {
    const auto c = static_cast<uint8_t>(10 + 20 * p.view_index);
    ASSERT_EQ(p.rgb, (std::array<uint8_t, 3>{c, c, c})) << "view " << p.view_index;
    seen.insert(p.view_index);
  }
  EXPECT_GT(seen.size(), 1u);
  EXPECT_EQ(colours.asked(), (std::vector<size_t>{0, 1, 2}));

  SolidColours failing;
  failing.fail_at_ = 2;
  CollectingSink ignored;
  EXPECT_THROW(RunSacFusion(views, TestOptions(), ignored, {}, {}, &failing), InputError);
}

TEST(SacFusionTest, DenseStrategyWithoutConsistencyGraphsIsAClearError) {
  SyntheticBlock block;
  const View a = NadirView(0, kEast, kNorth, 500.0);
  block.Add(a, PlaneDepth(a));
  SacOptions options = TestOptions();
  options.correspondence = "dense";
  CollectingSink sink;
  try {
    RunSacFusion(block.SacViews(), options, sink);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("consistency graph"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sacfuse
