// Plane-fit normals from depth on exact planes (known normals) and across a depth step.
#include "core/depth_normals.h"

#include <cmath>

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

}  // namespace
}  // namespace sacfuse
