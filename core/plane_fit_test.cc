// PlaneFit on hand-made points whose plane is known.
#include "core/plane_fit.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

TEST(PlaneFitTest, NormalOfATiltedPlaneAndItsEigenvalues) {
  PlaneFit fit;
  for (int i = -2; i <= 2; ++i) {
    for (int j = -2; j <= 2; ++j) fit.Add(Eigen::Vector3d(i, j, 0.5 * i + 3.0));  // z = 0.5 x + 3
  }
  EXPECT_EQ(fit.count(), 25);
  Eigen::Vector3d ev;
  const Eigen::Vector3d n = fit.Normal(&ev);
  const Eigen::Vector3d expected = Eigen::Vector3d(0.5, 0.0, -1.0).normalized();
  EXPECT_NEAR(std::abs(n.dot(expected)), 1.0, 1e-12);
  EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  EXPECT_NEAR(ev[0], 0.0, 1e-12);          // the points lie on the plane
  EXPECT_NEAR(ev[1], 2.0, 1e-12);          // variance of j in {-2..2}
  EXPECT_NEAR(ev[2], 2.0 * 1.25, 1e-12);   // along (1, 0, 0.5): variance 2 x |(1, 0.5)|^2
}

TEST(PlaneFitTest, CollinearPointsHaveTwoZeroEigenvalues) {
  PlaneFit fit;
  for (int i = 0; i < 5; ++i) fit.Add(Eigen::Vector3d(i, 2.0 * i, 0.0));
  Eigen::Vector3d ev;
  fit.Normal(&ev);
  EXPECT_NEAR(ev[0], 0.0, 1e-12);
  EXPECT_NEAR(ev[1], 0.0, 1e-12);
  EXPECT_GT(ev[2], 1.0);
}

}  // namespace
}  // namespace sacfuse
