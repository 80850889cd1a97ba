// The owned region of a run (core/owned_region.h): deciding whole patches at once must give the answer of testing
// every pixel, on a tilted view with random depths, for regions whose edges cross its footprint.
#include "core/owned_region.h"

#include <random>

#include <gtest/gtest.h>

#include "core/method_views.h"
#include "core/patch_grid.h"
#include "core/sac_test_scene.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::kNorth;

// A view tilted 35 degrees off nadir about its image x axis, with a tenth of the pixels invalid and depths drawn from
// [300, 700] m (rough: every patch's points spread far along the rays), or a slope from 500 to 600 m with +-2 m of
// noise (a surface).
struct TiltedView {
  View view;
  DepthMap depth;
  SacView sac;

  explicit TiltedView(bool rough) {
    view = testing::NadirView(0, kEast, kNorth, 500.0, 160, 120, 400.0);
    const Rigid3d world_from_cam = view.cam_from_world.Inverse();
    const Eigen::Quaterniond tilt(Eigen::AngleAxisd(35.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()));
    view.cam_from_world = Rigid3d{world_from_cam.rotation * tilt, world_from_cam.translation}.Inverse();
    depth = DepthMap(160, 120, 1, 0.0f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> z(300.0f, 700.0f), noise(-2.0f, 2.0f);
    std::uniform_int_distribution<int> tenth(0, 9);
    for (int row = 0; row < 120; ++row) {
      for (int col = 0; col < 160; ++col) {
        const float d = rough ? z(rng) : 500.0f + 100.0f * col / 160.0f + noise(rng);
        depth.at(row, col) = tenth(rng) == 0 ? 0.0f : d;
      }
    }
    sac = MakeSacView(view, &depth, nullptr, nullptr);
  }
};

size_t CountEveryPixel(const SacView& view, const PixelWindow& w, const OwnedRegion& region, size_t* valid) {
  size_t owned = 0;
  *valid = 0;
  for (int row = w.row_begin; row < w.row_end; ++row) {
    for (int col = w.col_begin; col < w.col_end; ++col) {
      const float d = view.depth->at(row, col);
      if (!IsValidDepth(d)) continue;
      ++*valid;
      if (region.Contains(PixelPoint(view, row, col, d))) ++owned;
    }
  }
  return owned;
}

// Checks every patch of two sizes against per-pixel tests for six regions; counts the patches decided whole.
void CheckAgainstEveryPixel(const TiltedView& tilted, int* all, int* none, int* some) {
  const SacView& view = tilted.sac;
  // The footprint's XY extent, to put the region's edges across it.
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (int row = 0; row < 120; ++row) {
    for (int col = 0; col < 160; ++col) {
      const float d = tilted.depth.at(row, col);
      if (!IsValidDepth(d)) continue;
      const Eigen::Vector2d xy = PixelPoint(view, row, col, d).head<2>();
      lo = lo.cwiseMin(xy);
      hi = hi.cwiseMax(xy);
    }
  }
  for (double fx : {0.2, 0.5, 0.8}) {
    for (double fy : {0.3, 0.6}) {
      OwnedRegion region;
      region.min = {lo.x() + fx * (hi.x() - lo.x()), -OwnedRegion::kInfinity};
      region.max = {OwnedRegion::kInfinity, lo.y() + fy * (hi.y() - lo.y())};
      for (const int size : {4, 16}) {
        const PatchGrid grid(120, 160, size, size);
        for (int p = 0; p < grid.size(); ++p) {
          const PixelWindow patch = grid.Patch(p);
          const WindowOwnership ownership = ClassifyWindow(view, patch, region);
          size_t valid = 0;
          const size_t owned = CountEveryPixel(view, patch, region, &valid);
          EXPECT_EQ(ownership.valid_pixels, valid);
          if (ownership.kind == WindowOwnership::kAll) {
            EXPECT_EQ(owned, valid);
          }
          if (ownership.kind == WindowOwnership::kNone) {
            EXPECT_EQ(owned, 0u);
          }
          *all += ownership.kind == WindowOwnership::kAll;
          *none += ownership.kind == WindowOwnership::kNone;
          *some += ownership.kind == WindowOwnership::kSome;
        }
      }
      size_t valid = 0;
      EXPECT_EQ(CountOwnedPixels(view, region), CountEveryPixel(view, {0, 120, 0, 160}, region, &valid));
    }
  }
}

TEST(OwnedRegionTest, PatchDecisionsAgreeWithEveryPixelsTest) {
  int all = 0, none = 0, some = 0;
  CheckAgainstEveryPixel(TiltedView(/*rough=*/true), &all, &none, &some);
  EXPECT_GT(all + none, 0);
  all = none = some = 0;
  CheckAgainstEveryPixel(TiltedView(/*rough=*/false), &all, &none, &some);
  // Decisive: most patches are decided whole; only those across an edge are tested pixel by pixel.
  EXPECT_GT(all, some);
  EXPECT_GT(none, some);
  EXPECT_GT(some, 0);
}

TEST(OwnedRegionTest, TheDefaultRegionOwnsEverything) {
  const TiltedView tilted(/*rough=*/false);
  const OwnedRegion everything;
  EXPECT_TRUE(everything.OwnsEverything());
  EXPECT_TRUE(everything.Contains({-1e300, 1e300, 0.0}));
  size_t valid = 0;
  CountEveryPixel(tilted.sac, {0, 120, 0, 160}, everything, &valid);
  EXPECT_EQ(CountOwnedPixels(tilted.sac, everything), valid);
  EXPECT_EQ(ClassifyWindow(tilted.sac, {0, 8, 0, 8}, everything).kind, WindowOwnership::kAll);
}

TEST(OwnedRegionTest, HalfOpen) {
  OwnedRegion region;
  region.min = {10.0, 20.0};
  region.max = {11.0, 21.0};
  EXPECT_TRUE(region.Contains({10.0, 20.0, 0.0}));
  EXPECT_FALSE(region.Contains({11.0, 20.5, 0.0}));
  EXPECT_FALSE(region.Contains({10.5, 21.0, 0.0}));
  EXPECT_FALSE(region.Contains({std::nextafter(10.0, 0.0), 20.5, 0.0}));
}

}  // namespace
}  // namespace sacfuse
