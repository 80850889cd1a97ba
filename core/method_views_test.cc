// Neighbour views and processing order of the comparison methods, on hand-made footprints.
#include "core/method_views.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

Box2d Box(double x0, double y0, double x1, double y1) {
  Box2d b;
  b.Extend({x0, y0});
  b.Extend({x1, y1});
  return b;
}

TEST(MethodViewsTest, NeighboursNeedOverlapAndSimilarDirectionsAndAreRankedByBoth) {
  const Eigen::Vector3d down(0, 0, -1);
  const Eigen::Vector3d tilted_30(std::sin(M_PI / 6), 0, -std::cos(M_PI / 6));
  const Eigen::Vector3d tilted_70(std::sin(70 * M_PI / 180), 0, -std::cos(70 * M_PI / 180));
  const std::vector<Box2d> boxes = {Box(0, 0, 10, 10),    // 0
                                           Box(5, 0, 15, 10),    // 1: half of 0
                                           Box(9.8, 0, 20, 10),  // 2: 2 % of 0
                                           Box(0, 0, 10, 10),    // 3: all of 0, tilted 30 degrees
                                           Box(0, 0, 10, 10),    // 4: all of 0, tilted 70 degrees
                                           Box2d{}};             // 5: empty
  const std::vector<Eigen::Vector3d> dirs = {down, down, down, tilted_30, tilted_70, down};
  NeighborViewOptions o;
  const auto n = NeighborsFromFootprints(boxes, dirs, o);
  EXPECT_EQ(n[0], (std::vector<uint32_t>{3, 1}));  // 1 x cos 30 = 0.87 beats 0.5 x 1
  EXPECT_TRUE(n[5].empty());
  o.max_views = 1;
  EXPECT_EQ(NeighborsFromFootprints(boxes, dirs, o)[0], (std::vector<uint32_t>{3}));
  o.max_views = 10;
  o.min_footprint_overlap = 0.01;
  EXPECT_EQ(NeighborsFromFootprints(boxes, dirs, o)[0], (std::vector<uint32_t>{3, 1, 2}));
}

TEST(MethodViewsTest, PrecisionOrderPutsTheSmallestUncertaintyFirstAndKeepsTiesInIndexOrder) {
  EXPECT_EQ(PrecisionOrder({3.0, 1.0, 3.0, 0.5, 1.0}), (std::vector<uint32_t>{3, 1, 4, 0, 2}));
  ViewPlan plan;
  plan.neighbors = {{1}, {0}};
  plan.order = {1, 0};
  EXPECT_NO_THROW(CheckViewPlan(plan, 2));
  plan.order = {1, 1};
  EXPECT_THROW(CheckViewPlan(plan, 2), Error);
  plan.order = {1, 0};
  plan.neighbors = {{0}, {0}};  // a view is not its own neighbour
  EXPECT_THROW(CheckViewPlan(plan, 2), Error);
}

}  // namespace
}  // namespace sacfuse
