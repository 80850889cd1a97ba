// Box2d: the two "empty" rules, closed edges, intersection and overlap areas, on hand-made boxes.
#include "core/box2d.h"

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

TEST(Box2dTest, DefaultIsEmptyAPointIsNotEmptyButHasNoArea) {
  Box2d b;
  EXPECT_TRUE(b.IsEmpty());
  EXPECT_FALSE(b.HasArea());
  EXPECT_EQ(b.Area(), 0.0);
  b.Extend(Eigen::Vector2d(2, 3));
  EXPECT_FALSE(b.IsEmpty());
  EXPECT_FALSE(b.HasArea());
  EXPECT_TRUE(b.Contains(2, 3));
  b.Extend(Eigen::Vector2d(2, 7));  // a line: still no area
  EXPECT_FALSE(b.HasArea());
  EXPECT_EQ(b.Area(), 0.0);
  b.Extend(Eigen::Vector2d(5, 4));
  EXPECT_TRUE(b.HasArea());
  EXPECT_DOUBLE_EQ(b.Area(), 3.0 * 4.0);
  EXPECT_EQ(b.Center(), Eigen::Vector2d(3.5, 5));
}

TEST(Box2dTest, ClosedEdgesIntersectionAndOverlap) {
  const Box2d a(0, 0, 10, 10);
  const Box2d touching(10, 0, 20, 10);
  EXPECT_TRUE(a.Contains(10, 10));
  EXPECT_FALSE(a.Contains(10.001, 5));
  EXPECT_TRUE(a.Intersects(touching));        // closed: a shared edge meets
  EXPECT_EQ(OverlapArea(a, touching), 0.0);   // but has no area
  EXPECT_FALSE(a.Intersects(Box2d(10.5, 0, 20, 10)));
  EXPECT_TRUE(a.Intersection(Box2d(10.5, 0, 20, 10)).IsEmpty());
  EXPECT_DOUBLE_EQ(OverlapArea(a, Box2d(5, -5, 15, 5)), 25.0);
  Box2d u = a;
  u.Extend(Box2d(-1, 2, 3, 12));
  EXPECT_EQ(u.min, Eigen::Vector2d(-1, 0));
  EXPECT_EQ(u.max, Eigen::Vector2d(10, 12));
  const Box2d e = a.Expanded(1.5);
  EXPECT_EQ(e.min, Eigen::Vector2d(-1.5, -1.5));
  EXPECT_DOUBLE_EQ(e.Width(), 13.0);
  EXPECT_TRUE(Box2d::Infinite().Contains(1e300, -1e300));
}

}  // namespace
}  // namespace sacfuse
