// Point tests before the collapse (core/point_verdicts.h) and the best-view redundancy (core/redundancy.h) on
// nadir views over a plane whose answers are known by construction (core/sac_test_scene.h).
#include "core/point_verdicts.h"

#include <algorithm>
#include <limits>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "core/method_views.h"
#include "core/redundancy.h"
#include "core/sac_fusion.h"
#include "core/sac_nodes.h"
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

// Three nadir views 4 m apart over a plane (exact depths); view 0 has a floating blob 20 m above the plane in a
// 10 x 10 pixel square of its image.
SyntheticBlock BlockWithFloater() {
  SyntheticBlock block;
  for (uint32_t i = 0; i < 3; ++i) {
    const View view = NadirView(i, kEast + 4.0 * i, kNorth, 500.0);
    DepthMap depth = PlaneDepth(view);
    if (i == 0) {
      for (int r = 40; r < 50; ++r) {
        for (int c = 55; c < 65; ++c) depth.at(r, c) -= 20.0f;
      }
    }
    block.Add(view, depth);
  }
  return block;
}

std::vector<std::vector<uint32_t>> AllOthers(size_t n) {
  std::vector<std::vector<uint32_t>> out(n);
  for (uint32_t v = 0; v < n; ++v) {
    for (uint32_t b = 0; b < n; ++b) {
      if (b != v) out[v].push_back(b);
    }
  }
  return out;
}

// The floater block with every other view judging each view.
class PointVerdictsTest : public ::testing::Test {
 protected:
  const SyntheticBlock block = BlockWithFloater();
  const std::vector<SacView> views = block.SacViews();
  const std::vector<std::vector<uint32_t>> others = AllOthers(views.size());
};

TEST_F(PointVerdictsTest, FloaterSeenThroughByTwoViewsIsFreeSpaceTheGroundPasses) {
  SacOptions options;
  options.min_consistent_views = 1;  // isolate the free-space test
  options.free_space_min_views = 2;
  const PointVerdicts verdicts(views, others, ConsultedViews(others), {}, options);
  EXPECT_EQ(verdicts.At(0, 45, 60), PointVerdict::kFreeSpace);  // both others see the ground behind
  EXPECT_EQ(verdicts.At(0, 10, 10), PointVerdict::kPasses);
  EXPECT_EQ(verdicts.At(1, 45, 60), PointVerdict::kPasses);
  // Asking for three views that see through it: only two can, so it passes that test.
  options.free_space_min_views = 3;
  EXPECT_EQ(PointVerdicts(views, others, ConsultedViews(others), {}, options).At(0, 45, 60), PointVerdict::kPasses);
  // Off: nothing is free space.
  options.free_space_min_views = 0;
  EXPECT_EQ(PointVerdicts(views, others, ConsultedViews(others), {}, options).At(0, 45, 60), PointVerdict::kPasses);
}

// The judges are asked in their list's order, and a point that none of the first free_space_early_pass_views sees
// through passes without the rest. Views 4 m west, 4 m and 8 m east of view 0 (which holds the floater); view 1 has
// no depth (so never sees through the floater), views 2 and 3 see the ground behind it.
TEST(PointVerdictsEarlyPassTest, PointNoneOfTheFirstJudgesSeesThroughPasses) {
  SyntheticBlock block;
  const double east_offset_m[4] = {0.0, 4.0, 8.0, -4.0};
  for (uint32_t i = 0; i < 4; ++i) {
    const View view = NadirView(i, kEast + east_offset_m[i], kNorth, 500.0);
    DepthMap depth = PlaneDepth(view);
    for (int r = 0; r < depth.height; ++r) {
      for (int c = 0; c < depth.width; ++c) {
        if (i == 0 && r >= 40 && r < 50 && c >= 55 && c < 65) depth.at(r, c) -= 20.0f;
        if (i == 1) depth.at(r, c) = 0.0f;  // no depth
      }
    }
    block.Add(view, depth);
  }
  const std::vector<SacView> views = block.SacViews();
  const std::vector<std::vector<uint32_t>> neighbors = AllOthers(views.size());
  auto verdict = [&](std::vector<uint32_t> judges_of_0, int early_pass) {
    std::vector<std::vector<uint32_t>> judges = neighbors;
    judges[0] = std::move(judges_of_0);
    SacOptions options;
    options.min_consistent_views = 1;  // isolate the free-space test
    options.free_space_min_views = 2;
    options.free_space_early_pass_views = early_pass;
    return PointVerdicts(views, neighbors, ConsultedViews(judges), {}, options).At(0, 45, 60);
  };
  EXPECT_EQ(verdict({1, 2, 3}, 0), PointVerdict::kFreeSpace);  // every judge asked
  EXPECT_EQ(verdict({1, 2, 3}, 1), PointVerdict::kPasses);     // judge 1 does not see through: it passes
  EXPECT_EQ(verdict({1, 2, 3}, 2), PointVerdict::kFreeSpace);  // judge 2 does: the rest are asked too
  EXPECT_EQ(verdict({2, 1, 3}, 1), PointVerdict::kFreeSpace);
  EXPECT_EQ(verdict({0, 1, 2, 3}, 1), PointVerdict::kPasses);  // the view itself is not one of its judges
  EXPECT_EQ(verdict({0, 2, 1, 3}, 1), PointVerdict::kFreeSpace);
}

// Judges that are not outlier neighbours are read through the depth ceiling first (DepthCeiling): a pit 20 m deep
// in one pixel of view 1 raises the ceiling of its whole block, but only the view-0 pixel that lands on the pit is
// seen through; its neighbour, landing in the same block, still passes. Same verdicts as reading every pixel.
TEST_F(PointVerdictsTest, FreeSpaceThroughTheDepthCeilingMatchesEveryPixelRead) {
  SyntheticBlock pit = BlockWithFloater();
  pit.depths[1].at(10, 16) += 20.0f;  // view 0's pixel (10, 40) lands here (view 1 is 24 pixels further east)
  const auto pit_views = pit.SacViews();
  SacOptions options;
  options.min_consistent_views = 1;
  options.free_space_min_views = 1;
  options.free_space_window_px = 0;  // the pit is one pixel: with a window its neighbours would agree
  const std::vector<std::vector<uint32_t>> none(pit_views.size());
  const PointVerdicts through_ceiling(pit_views, none, ConsultedViews(others), {}, options);
  const PointVerdicts every_read(pit_views, others, ConsultedViews(others), {}, options);
  EXPECT_EQ(through_ceiling.At(0, 10, 40), PointVerdict::kFreeSpace);
  EXPECT_EQ(through_ceiling.At(0, 10, 41), PointVerdict::kPasses);
  EXPECT_EQ(through_ceiling.At(0, 45, 60), PointVerdict::kFreeSpace);  // the floater
  for (int r = 0; r < 90; r += 3) {
    for (int c = 0; c < 120; ++c) ASSERT_EQ(through_ceiling.At(0, r, c), every_read.At(0, r, c)) << r << " " << c;
  }
}

// View 0's pixel (10, 70) lands on view 1's (10, 46) and view 2's (10, 22). Both have a pit 20 m deep that begins
// exactly there, so a pixel of registration error would put view 0's point on their near side: with a window of one
// pixel the plane beside it agrees and the point is not free space; without one, or one column further in
// (10, 75: the whole window is pit) it is. Where view 0 itself has a foreground edge within the band (a pit of its
// own two columns away), the pixel alone judges.
TEST_F(PointVerdictsTest, AnEdgeOnePixelAwayInTheJudgesIsNoFreeSpaceUnlessTheOwnViewHasOne) {
  SyntheticBlock pits = BlockWithFloater();
  for (int r = 5; r <= 15; ++r) {
    for (int c = 46; c <= 55; ++c) pits.depths[1].at(r, c) += 20.0f;
    for (int c = 22; c <= 31; ++c) pits.depths[2].at(r, c) += 20.0f;
  }
  SacOptions options;
  options.min_consistent_views = 1;  // isolate the free-space test
  options.free_space_min_views = 2;
  ASSERT_EQ(options.free_space_window_px, 1);  // the defaults
  ASSERT_EQ(options.free_space_edge_band_px, 2);
  auto verdict = [&](const SyntheticBlock& block, const SacOptions& o, int row, int col) {
    const auto block_views = block.SacViews();
    return PointVerdicts(block_views, others, ConsultedViews(others), {}, o).At(0, row, col);
  };
  EXPECT_EQ(verdict(pits, options, 10, 70), PointVerdict::kPasses);
  EXPECT_EQ(verdict(pits, options, 10, 75), PointVerdict::kFreeSpace);
  SacOptions pixel_alone = options;
  pixel_alone.free_space_window_px = 0;
  EXPECT_EQ(verdict(pits, pixel_alone, 10, 70), PointVerdict::kFreeSpace);

  SyntheticBlock own_edge = pits;
  for (int r = 5; r <= 15; ++r) {
    for (int c = 72; c <= 80; ++c) own_edge.depths[0].at(r, c) += 20.0f;
  }
  EXPECT_EQ(verdict(own_edge, options, 10, 70), PointVerdict::kFreeSpace);
  SacOptions narrow_band = options;
  narrow_band.free_space_edge_band_px = 1;
  EXPECT_EQ(verdict(own_edge, narrow_band, 10, 70), PointVerdict::kPasses);
}

TEST(DepthCeilingTest, DeepestValidDepthPerBlock) {
  DepthMap depth(10, 9, 1, 5.0f);
  depth.at(1, 2) = 7.0f;
  depth.at(3, 9) = 0.0f;                      // invalid: ignored
  for (int r = 8; r < 9; ++r) {
    for (int c = 8; c < 10; ++c) depth.at(r, c) = 0.0f;  // a block with no valid depth
  }
  const DepthCeiling ceiling(depth);
  EXPECT_EQ(ceiling.At(0, 0), 7.0f);
  EXPECT_EQ(ceiling.At(7, 7), 7.0f);
  EXPECT_EQ(ceiling.At(3, 9), 5.0f);
  EXPECT_EQ(ceiling.At(8, 0), 5.0f);
  EXPECT_EQ(ceiling.At(8, 9), -std::numeric_limits<float>::infinity());
}

TEST_F(PointVerdictsTest, OutlierTestNeedsAgreeingViews) {
  SacOptions options;
  options.min_consistent_views = 2;
  options.free_space_min_views = 0;
  const PointVerdicts verdicts(views, others, ConsultedViews(others), {}, options);
  EXPECT_EQ(verdicts.At(0, 45, 60), PointVerdict::kOutlier);  // nobody agrees with the floater
  // Seen by no other view: an outlier as soon as two views are asked for.
  EXPECT_EQ(verdicts.At(0, 45, 5), PointVerdict::kOutlier);
  EXPECT_EQ(verdicts.At(0, 45, 100), PointVerdict::kPasses);  // seen and agreed by views 1, 2
  // Invalid depth pixels get no verdict.
  SyntheticBlock holes = BlockWithFloater();
  holes.depths[2].at(5, 5) = 0.0f;
  const auto hole_views = holes.SacViews();
  EXPECT_EQ(PointVerdicts(hole_views, others, ConsultedViews(others), {}, options).At(2, 5, 5), PointVerdict::kInvalid);
}

// Verdicts are judged on first ask and remembered: asked in any order, from many threads, they are the same.
TEST_F(PointVerdictsTest, VerdictsDoNotDependOnTheOrderTheyAreAskedIn) {
  SacOptions options;
  options.min_consistent_views = 2;
  options.free_space_min_views = 2;
  const PointVerdicts forward(views, others, ConsultedViews(others), {}, options);
  const PointVerdicts backward(views, others, ConsultedViews(others), {}, options);
  const PointVerdicts parallel(views, others, ConsultedViews(others), {}, options);
  const DepthMap& depth = block.depths[0];
  const int n = static_cast<int>(depth.num_pixels());
  std::vector<PointVerdict> in_order(n), in_reverse(n);
  for (int i = 0; i < n; ++i) in_order[i] = forward.At(0, i / depth.width, i % depth.width);
  for (int i = n - 1; i >= 0; --i) in_reverse[i] = backward.At(0, i / depth.width, i % depth.width);
  // Four askers per pixel, racing.
  std::vector<std::vector<PointVerdict>> in_parallel(4, std::vector<PointVerdict>(n));
  tbb::parallel_for(0, 4 * n, [&](int i) {
    const int pixel = (i * 7919) % n;  // scattered (7919 is prime, n is not a multiple of it)
    in_parallel[i / n][pixel] = parallel.At(0, pixel / depth.width, pixel % depth.width);
  });
  EXPECT_EQ(in_order, in_reverse);
  for (const auto& asked : in_parallel) EXPECT_EQ(in_order, asked);
  // And the second ask returns what the first judged.
  for (int i = 0; i < n; ++i) ASSERT_EQ(forward.At(0, i / depth.width, i % depth.width), in_order[i]);
  // The 10 x 10 floater fails its tests; most of the ground passes.
  for (int r = 40; r < 50; ++r) {
    for (int c = 55; c < 65; ++c) EXPECT_NE(in_order[r * depth.width + c], PointVerdict::kPasses);
  }
  EXPECT_GT(std::count(in_order.begin(), in_order.end(), PointVerdict::kPasses), n / 2);
}

// Best-view collapse alone: no outlier or free-space test.
SacOptions BestViewOnly() {
  SacOptions options;
  options.min_consistent_views = 1;
  options.free_space_min_views = 0;
  options.collapse = "best_view";
  return options;
}

// Netlet labels in which every node keeps its own view.
std::vector<uint32_t> OwnLabels(const NodeTable& nodes) {
  std::vector<uint32_t> labels(nodes.nodes.size());
  for (size_t i = 0; i < nodes.nodes.size(); ++i) labels[i] = nodes.nodes[i].view;
  return labels;
}

// Two views of one plane, view 0 from half the height (4x more precise: sigma ~ z^2 / f). Best view: every pixel of
// view 1 over view 0's footprint is redundant; the rest of view 1 is kept; view 0 keeps all its pixels.
TEST(RedundancyTest, BestViewEmitsAloneWhereItSeesAndTheOtherViewFillsTheRest) {
  SyntheticBlock block;
  block.Add(NadirView(0, kEast, kNorth, 250.0), PlaneDepth(NadirView(0, kEast, kNorth, 250.0)));
  block.Add(NadirView(1, kEast + 8.0, kNorth, 500.0), PlaneDepth(NadirView(1, kEast + 8.0, kNorth, 500.0)));
  const auto views = block.SacViews();
  const auto others = AllOthers(views.size());
  const SacOptions options = BestViewOnly();
  const PointVerdicts verdicts(views, others, ConsultedViews(others), {}, options);
  const NodeTable nodes = BuildNodes(views);
  const NodeLabels own_labels(OwnLabels(nodes));
  // View 1's pixel under view 0's footprint centre, and one far outside it.
  const Eigen::Vector3d inside = views[1].world_from_cam * views[1].depth_camera.Unproject(60.5 - 48.0, 45.5, 500.0);
  EXPECT_TRUE(BetterViewEmits(views, 1, inside, 500.0, others[1], {}, nodes, own_labels, verdicts, options));
  const Eigen::Vector3d outside = views[1].world_from_cam * views[1].depth_camera.Unproject(110.5, 45.5, 500.0);
  EXPECT_FALSE(BetterViewEmits(views, 1, outside, 500.0, others[1], {}, nodes, own_labels, verdicts, options));
  // View 0 has no better view.
  const Eigen::Vector3d centre0 = views[0].world_from_cam * views[0].depth_camera.Unproject(60.5, 45.5, 250.0);
  EXPECT_FALSE(BetterViewEmits(views, 0, centre0, 250.0, others[0], {}, nodes, own_labels, verdicts, options));

  // End to end: view 0 emits all its pixels, view 1 only what view 0 does not see, and the ground is covered.
  CollectingSink sink;
  const SacStats stats = RunSacFusion(views, options, sink);
  EXPECT_EQ(stats.emitted_per_view[0], block.depths[0].num_pixels());
  EXPECT_GT(stats.collapse.redundant, 0u);
  // View 0 covers east +-1.25 m .. view 1 covers +8 +-10 m: view 1 keeps about (18.75 - 1.25) / 20 of its columns.
  const double kept_fraction = static_cast<double>(stats.emitted_per_view[1]) / block.depths[1].num_pixels();
  EXPECT_NEAR(kept_fraction, 17.5 / 20.0, 0.06);
}

// The better-view search tries the most precise views first: lower, then (same height) lower noise factor.
TEST(RedundancyTest, SearchOrderIsMostPreciseFirst) {
  SyntheticBlock block;
  const double heights_m[] = {500.0, 250.0, 500.0, 400.0};
  for (uint32_t i = 0; i < 4; ++i) {
    const View view = NadirView(i, kEast + 2.0 * i, kNorth, heights_m[i]);
    block.Add(view, PlaneDepth(view));
  }
  const auto views = block.SacViews();
  const auto others = AllOthers(views.size());
  const Eigen::Vector3d anywhere = Eigen::Vector3d::Zero();
  EXPECT_EQ(RedundancySearchOrder(views, ConsultedViews(others), {}).At(0, anywhere), (std::vector<uint32_t>{1, 3, 2}));
  // View 1 noisier by 5x (k z^2 = 5 x 250^2 > 500^2): last; view 2 less noisy than view 0 at the same height.
  EXPECT_EQ(RedundancySearchOrder(views, ConsultedViews(others), {1.0, 5.0, 0.9, 1.0}).At(0, anywhere),
            (std::vector<uint32_t>{3, 2, 1}));
}

// A better view whose pixel is an outlier does not take the surface away from the other view: no hole.
TEST(RedundancyTest, BetterViewWhosePixelIsDroppedDoesNotMakeAHole) {
  SyntheticBlock block;
  const View fine = NadirView(0, kEast, kNorth, 250.0);
  const View coarse = NadirView(1, kEast, kNorth, 500.0);
  block.Add(fine, PlaneDepth(fine));
  block.Add(coarse, PlaneDepth(coarse));
  const auto views = block.SacViews();
  const auto others = AllOthers(views.size());
  const SacOptions options = BestViewOnly();
  const NodeTable nodes = BuildNodes(views);
  const NodeLabels own_labels(OwnLabels(nodes));
  const PointVerdicts verdicts(views, others, ConsultedViews(others), {}, options);
  const Eigen::Vector3d centre = views[1].world_from_cam * views[1].depth_camera.Unproject(60.5, 45.5, 500.0);
  EXPECT_TRUE(BetterViewEmits(views, 1, centre, 500.0, others[1], {}, nodes, own_labels, verdicts, options));
  // Every pixel of the fine view an outlier (it has no neighbour to agree with, and two consistent views are
  // required): the coarse view keeps its pixel.
  SacOptions strict = options;
  strict.min_consistent_views = 2;
  const PointVerdicts fine_outliers(views, {{}, {0}}, ConsultedViews(others), {}, strict);
  EXPECT_EQ(fine_outliers.At(0, 45, 60), PointVerdict::kOutlier);
  EXPECT_FALSE(BetterViewEmits(views, 1, centre, 500.0, others[1], {}, nodes, own_labels, fine_outliers, strict));
  // And a fine pixel whose Netlet chose the coarse view does not count either (it is collapsed by the Netlet rule).
  const NodeLabels all_coarse(std::vector<uint32_t>(nodes.nodes.size(), 1));
  EXPECT_FALSE(BetterViewEmits(views, 1, centre, 500.0, others[1], {}, nodes, all_coarse, verdicts, options));
}


// Weak support. Four nadir views 500 m above the plane (GSD 1/6 m), at 0, +4, +8 and -4 m east. A 2 m square patch
// 3 m above the plane (a matcher's blunder: views 0 and 1 share it, as the two views of one stereo pair do) lies
// where views 2 and 3 found no depth (a 6 m square hole around it). Views 2 and 3 could see the patch: they are
// unmatched there, so the patch needs 3 agreeing depth maps and has 2. Where an occluder lies in front of it within
// the window (the hole is an occlusion), or where weak support is off, the patch passes as before. At view 0's west
// edge the plane is seen by view 3 alone (views 1 and 2 look elsewhere): one other view is all that can confirm it,
// so it passes.
class WeakSupportTest : public ::testing::Test {
 protected:
  static constexpr double kAltitudeM = 500.0;
  static constexpr double kPatchRiseM = 3.0;
  static constexpr int kSpikeRow = 45, kSpikeCol = 72;  // on the patch in view 0
  static constexpr int kEdgeRow = 45, kEdgeCol = 8;     // view 0's plane 8.5 m west of its centre

  // Raises the depths of `view` that look at the square [x0, x1] x [y0, y1] (offsets east / north of the scene
  // origin, metres) lifted by kPatchRiseM; invalidates (hole) those whose plane point lies in [hx0, hx1] x [hy0, hy1]
  // and not on the patch.
  static DepthMap Render(const View& view, bool patch, bool hole) {
    DepthMap depth = PlaneDepth(view);
    const Rigid3d world_from_cam = view.cam_from_world.Inverse();
    for (int r = 0; r < depth.height; ++r) {
      for (int c = 0; c < depth.width; ++c) {
        const Eigen::Vector3d ray = world_from_cam.rotation * view.camera.Unproject(c + 0.5, r + 0.5, 1.0);
        const double t_patch = (kGroundZ + kPatchRiseM - world_from_cam.translation.z()) / ray.z();
        const Eigen::Vector3d on_patch = world_from_cam.translation + t_patch * ray;
        const double px = on_patch.x() - kEast, py = on_patch.y() - kNorth;
        if (patch && px >= 1.0 && px <= 3.0 && py >= -1.0 && py <= 1.0) {
          depth.at(r, c) = static_cast<float>(t_patch);
          continue;
        }
        const double t = depth.at(r, c);
        const Eigen::Vector3d on_plane = world_from_cam.translation + t * ray;
        const double gx = on_plane.x() - kEast, gy = on_plane.y() - kNorth;
        if (hole && gx >= -1.0 && gx <= 5.0 && gy >= -3.0 && gy <= 3.0) depth.at(r, c) = 0.0f;
      }
    }
    return depth;
  }

  static SyntheticBlock Block() {
    SyntheticBlock block;
    const double east_offset_m[4] = {0.0, 4.0, 8.0, -4.0};
    for (uint32_t i = 0; i < 4; ++i) {
      const View view = NadirView(i, kEast + east_offset_m[i], kNorth, kAltitudeM);
      block.Add(view, Render(view, /*patch=*/i <= 1, /*hole=*/i >= 2));
    }
    return block;
  }

  static SacOptions WeakSupport() {
    SacOptions options;
    options.weak_support_min_views = 3;
    return options;
  }

  static PointVerdict VerdictAt(const SyntheticBlock& block, const SacOptions& options, int row, int col) {
    const std::vector<SacView> views = block.SacViews();
    const std::vector<std::vector<uint32_t>> others = AllOthers(views.size());
    return PointVerdicts(views, others, ConsultedViews(others), {}, options).At(0, row, col);
  }
};

TEST_F(WeakSupportTest, ABlunderOnlyItsPartnerConfirmsIsRemovedWhereOtherViewsFoundNothing) {
  const SyntheticBlock block = Block();
  SacOptions defaults;
  ASSERT_EQ(defaults.weak_support_min_views, 0);  // off by default
  defaults.weak_support_min_views = 3;
  ASSERT_NEAR(block.depths[0].at(kSpikeRow, kSpikeCol), kAltitudeM - kPatchRiseM, 1e-3);  // on the patch
  EXPECT_EQ(VerdictAt(block, defaults, kSpikeRow, kSpikeCol), PointVerdict::kOutlier);
  SacOptions off = defaults;
  off.weak_support_min_views = 0;
  EXPECT_EQ(VerdictAt(block, off, kSpikeRow, kSpikeCol), PointVerdict::kPasses);  // view 1 agrees: 2 of 2 asked
  // The plane west of the hole, seen and confirmed by views 1 and 3: 3 agreeing maps, it passes.
  EXPECT_EQ(VerdictAt(block, defaults, 45, 40), PointVerdict::kPasses);
}

TEST_F(WeakSupportTest, AHoleBesideAnOccluderIsNoMissingSupport) {
  SyntheticBlock block = Block();
  const std::vector<SacView> views = block.SacViews();
  const Eigen::Vector3d spike =
      PixelPoint(views[0], kSpikeRow, kSpikeCol, block.depths[0].at(kSpikeRow, kSpikeCol));
  for (uint32_t b : {2u, 3u}) {
    // A valid depth 100 m in front of the spike 5 pixels from its projection: the hole may be its occlusion.
    const DepthLookup hit = ProjectIntoDepth(views[b], views[b].PointInCamera(spike));
    ASSERT_TRUE(hit.inside);
    ASSERT_EQ(block.depths[b].at(hit.row, hit.col), 0.0f);
    block.depths[b].at(hit.row, hit.col + 5) = static_cast<float>(hit.z_m - 100.0);
  }
  EXPECT_EQ(VerdictAt(block, WeakSupport(), kSpikeRow, kSpikeCol), PointVerdict::kPasses);
}

TEST_F(WeakSupportTest, ASurfaceOnlyOneOtherViewSeesAtTheBlockEdgeIsKept) {
  SyntheticBlock block = Block();
  const std::vector<SacView> views = block.SacViews();
  const Eigen::Vector3d edge = PixelPoint(views[0], kEdgeRow, kEdgeCol, block.depths[0].at(kEdgeRow, kEdgeCol));
  ASSERT_FALSE(ProjectIntoDepth(views[1], views[1].PointInCamera(edge)).inside);
  ASSERT_FALSE(ProjectIntoDepth(views[2], views[2].PointInCamera(edge)).inside);
  ASSERT_TRUE(ProjectIntoDepth(views[3], views[3].PointInCamera(edge)).inside);
  EXPECT_EQ(VerdictAt(block, WeakSupport(), kEdgeRow, kEdgeCol), PointVerdict::kPasses);
  // Where view 3 has no depth either, nothing confirms it (as before).
  const DepthLookup in3 = ProjectIntoDepth(views[3], views[3].PointInCamera(edge));
  block.depths[3].at(in3.row, in3.col) = 0.0f;
  EXPECT_EQ(VerdictAt(block, WeakSupport(), kEdgeRow, kEdgeCol), PointVerdict::kOutlier);
}

// The rim rule (weak_support_rim_px): a blunder 2 m above the plane at view 0's west edge, matched alike by view 3,
// the one other view that sees the place (a stereo partner shares the match). Away from holes of view 0's own map it
// passes with view 3's confirmation (2 of 2 maps); beside a hole of view 0's map (the rim of what the matcher matched)
// it needs weak_support_min_views = 3 maps and is removed, while the plane 4 pixels from that hole is kept.
TEST_F(WeakSupportTest, ABlunderOnTheRimOfItsOwnMatchedRegionNeedsTheWeakSupportViews) {
  SyntheticBlock block = Block();
  block.depths[0].at(kEdgeRow, kEdgeCol) -= 2.0f;
  {
    const std::vector<SacView> views = block.SacViews();
    const Eigen::Vector3d blunder =
        PixelPoint(views[0], kEdgeRow, kEdgeCol, block.depths[0].at(kEdgeRow, kEdgeCol));
    const DepthLookup in3 = ProjectIntoDepth(views[3], views[3].PointInCamera(blunder));
    ASSERT_TRUE(in3.inside);
    block.depths[3].at(in3.row, in3.col) = static_cast<float>(in3.z_m);  // the partner's shared error
  }
  SacOptions options = WeakSupport();
  ASSERT_EQ(options.weak_support_rim_px, 2);  // the default
  EXPECT_EQ(VerdictAt(block, options, kEdgeRow, kEdgeCol), PointVerdict::kPasses);  // no hole near: 2 of 2 agree

  block.depths[0].at(kEdgeRow, kEdgeCol + 2) = 0.0f;  // a hole 2 pixels east: the pixel is on the rim
  EXPECT_EQ(VerdictAt(block, options, kEdgeRow, kEdgeCol), PointVerdict::kOutlier);
  EXPECT_EQ(VerdictAt(block, options, kEdgeRow, kEdgeCol + 6), PointVerdict::kPasses);  // 4 pixels from the hole
  SacOptions no_rim = options;
  no_rim.weak_support_rim_px = 0;
  EXPECT_EQ(VerdictAt(block, no_rim, kEdgeRow, kEdgeCol), PointVerdict::kPasses);
  SacOptions off = options;
  off.weak_support_min_views = 0;  // the rim rule belongs to weak support
  EXPECT_EQ(VerdictAt(block, off, kEdgeRow, kEdgeCol), PointVerdict::kPasses);
}


// Independent support: the same blunder patch, made by the stereo pair of views 0 and 1 (matching partners: each
// confirms the other's error), where views 2 and 3, matched in other pairs, found nothing. With the partners known,
// no independent view confirms the patch and two could see it but have no depth: it is removed. Where view 2 also
// put the patch there (an independent match agreeing), one confirms it against one unmatched and it passes; where
// every view is a partner of view 0, or the partners are unknown, the rule does not act.
TEST_F(WeakSupportTest, IndependentSupportDoubtsWhatOnlyTheStereoPartnerConfirms) {
  SyntheticBlock block = Block();
  const std::vector<std::vector<uint32_t>> pairs = {{1}, {0}, {3}, {2}};  // pairs (0, 1) and (2, 3)
  for (size_t i = 0; i < 4; ++i) block.views[i].matching_partners = pairs[i];
  SacOptions options;
  ASSERT_FALSE(options.independent_support);  // off by default
  EXPECT_EQ(VerdictAt(block, options, kSpikeRow, kSpikeCol), PointVerdict::kPasses);  // view 1 agrees: 2 of 2
  options.independent_support = true;
  EXPECT_EQ(VerdictAt(block, options, kSpikeRow, kSpikeCol), PointVerdict::kOutlier);  // 0 independent, 2 unmatched
  // The plane west of the patch, confirmed by views 1 and 3 (3 independent of view 0), passes.
  EXPECT_EQ(VerdictAt(block, options, 45, 40), PointVerdict::kPasses);

  SyntheticBlock unknown = block;  // the input does not name the partners
  for (View& view : unknown.views) view.matching_partners.clear();
  EXPECT_EQ(VerdictAt(unknown, options, kSpikeRow, kSpikeCol), PointVerdict::kPasses);

  SyntheticBlock all_partners = block;  // view 0 was matched with every other view: none is independent of it
  all_partners.views[0].matching_partners = {1, 2, 3};
  EXPECT_EQ(VerdictAt(all_partners, options, kSpikeRow, kSpikeCol), PointVerdict::kPasses);

  {  // View 2 matched the patch too: 1 independent confirmation against 1 unmatched view (3).
    const std::vector<SacView> views = block.SacViews();
    const Eigen::Vector3d spike = PixelPoint(views[0], kSpikeRow, kSpikeCol, block.depths[0].at(kSpikeRow, kSpikeCol));
    const DepthLookup in2 = ProjectIntoDepth(views[2], views[2].PointInCamera(spike));
    ASSERT_TRUE(in2.inside);
    block.depths[2].at(in2.row, in2.col) = static_cast<float>(in2.z_m);
  }
  EXPECT_EQ(VerdictAt(block, options, kSpikeRow, kSpikeCol), PointVerdict::kPasses);
}

}  // namespace
}  // namespace sacfuse
