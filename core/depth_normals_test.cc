// Plane-fit normals from depth on exact planes (known normals) and across a depth step.
#include "core/depth_normals.h"

#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include <gtest/gtest.h>

#include "core/method_test_scene.h"
#include "core/sac_test_scene.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::kGroundZ;
using testing::kNorth;
using testing::NadirView;

Eigen::Vector3d NormalAt(const NormalMap& n, int row, int col) {
  return {n.at(row, col, 0), n.at(row, col, 1), n.at(row, col, 2)};
}

TEST(DepthNormalsTest, HorizontalAndTiltedPlanesGiveTheirNormalsFacingTheCamera) {
  const View view = NadirView(0, kEast, kNorth, 500.0);
  for (const double slope : {0.0, 1.0, -0.5}) {
    const DepthMap depth = testing::TiltedPlaneDepth(view, kGroundZ, kEast, slope);
    const SacView sv = MakeSacView(view, &depth, nullptr, nullptr);
    const NormalMap normals = PlaneFitNormalsInWorld(sv, 2);
    const Eigen::Vector3d expected = Eigen::Vector3d(-slope, 0.0, 1.0).normalized();  // up, toward the camera
    for (const auto& [row, col] : std::vector<std::pair<int, int>>{{0, 0}, {45, 60}, {89, 119}, {10, 100}}) {
      EXPECT_LT((NormalAt(normals, row, col) - expected).norm(), 1e-4) << "slope " << slope << " at " << row << ","
                                                                        << col;
    }
  }
}

TEST(DepthNormalsTest, DepthStepsDoNotTiltTheNormalsOfEitherSide) {
  // A 20 m step (a roof edge) in the middle column: both sides stay horizontal up to the edge.
  const View view = NadirView(0, kEast, kNorth, 500.0);
  DepthMap depth = testing::TiltedPlaneDepth(view, kGroundZ, kEast, 0.0);
  for (int r = 0; r < depth.height; ++r) {
    for (int c = 60; c < depth.width; ++c) depth.at(r, c) -= 20.0f;
  }
  depth.at(30, 30) = 0.0f;  // an invalid pixel has no normal
  const SacView sv = MakeSacView(view, &depth, nullptr, nullptr);
  const NormalMap normals = PlaneFitNormalsInWorld(sv, 2);
  for (const int col : {58, 59, 60, 61}) {
    EXPECT_GT(NormalAt(normals, 45, col).z(), 0.9999) << "column " << col;
  }
  EXPECT_EQ(NormalAt(normals, 30, 30).squaredNorm(), 0.0);
}

TEST(DepthNormalsTest, LazyNormalsEqualTheWholeMapBitForBitWhenReadFromManyThreads) {
  // A tilted plane with a roof step and invalid pixels, the normals in a rotated world frame.
  View view = NadirView(0, kEast, kNorth, 500.0);
  view.cam_from_world.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())) *
                                 view.cam_from_world.rotation;
  DepthMap depth = testing::TiltedPlaneDepth(NadirView(0, kEast, kNorth, 500.0), kGroundZ, kEast, 0.4);
  for (int r = 20; r < 50; ++r) {
    for (int c = 40; c < 90; ++c) depth.at(r, c) -= 15.0f;
  }
  for (int k = 0; k < 200; ++k) depth.at((k * 37) % depth.height, (k * 53) % depth.width) = 0.0f;
  const SacView sv = MakeSacView(view, &depth, nullptr, nullptr);
  const NormalMap whole = PlaneFitNormalsInWorld(sv, 1);
  const LazyPlaneFitNormals lazy(sv, 1);
  const int pixels = depth.width * depth.height;
  // Every pixel asked for three times, by interleaved threads and in a scattered order, so that a pixel is often
  // asked for again while or after another thread stored it.
  std::vector<Eigen::Vector3f> got(3 * static_cast<size_t>(pixels));
  tbb::parallel_for(0, 3 * pixels, [&](int k) {
    const int i = static_cast<int>((static_cast<int64_t>(k) * 7919) % pixels);
    got[static_cast<size_t>(k)] = lazy.At(i / depth.width, i % depth.width);
  });
  int zero = 0;
  for (int k = 0; k < 3 * pixels; ++k) {
    const int i = static_cast<int>((static_cast<int64_t>(k) * 7919) % pixels);
    const int row = i / depth.width, col = i % depth.width;
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(got[static_cast<size_t>(k)][c], whole.at(row, col, c)) << "pixel " << row << "," << col << " ask " << k;
    }
    zero += got[static_cast<size_t>(k)].squaredNorm() == 0.0f;
  }
  EXPECT_GE(zero, 3 * 200);  // the invalid pixels have none
  EXPECT_LT(zero, 3 * pixels / 10);
  EXPECT_NEAR(lazy.At(30, 60).norm(), 1.0f, 1e-6f);  // on the roof: a unit normal
}

}  // namespace
}  // namespace sacfuse
