#include "eval/top_surface.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

// 1 m cells over x, y in [0, 10): ground at 0 everywhere, a 10 m roof over columns x in [5, 10).
std::vector<Eigen::Vector3f> WallScene() {
  std::vector<Eigen::Vector3f> pts;
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) pts.emplace_back(x + 0.5f, y + 0.5f, x >= 5 ? 10.0f : 0.0f);
  }
  return pts;
}

TEST(TopSurfaceTest, WallNeighboursTakeTheRoofButStayVisible) {
  const TopSurface top(WallScene(), 1.0);
  EXPECT_DOUBLE_EQ(top.OccupiedArea(), 100.0);
  const auto street = top.Query(4.5f, 5.5f);  // ground cell right beside the wall
  EXPECT_TRUE(street.observed);
  EXPECT_FLOAT_EQ(street.top, 10.0f);    // below the roof -> facade points here are unobserved
  EXPECT_FLOAT_EQ(street.bottom, 0.0f);
  EXPECT_FLOAT_EQ(street.occluder, 0.0f);  // a wall on one side hides nothing
  const auto open = top.Query(1.5f, 5.5f);
  EXPECT_FLOAT_EQ(open.top, 0.0f);
  const auto roof = top.Query(7.5f, 5.5f);
  EXPECT_FLOAT_EQ(roof.bottom, 10.0f);
  EXPECT_FALSE(top.Query(20.0f, 5.0f).observed);  // beyond the reference
  EXPECT_TRUE(top.Query(10.5f, 5.0f).observed);   // next to its last cell
}

TEST(TopSurfaceTest, CanopyAndNarrowSlotsOcclude) {
  auto pts = WallScene();
  pts.emplace_back(3.5f, 5.5f, 8.0f);  // west of the slot at x = 4: an 8 m high point (tree or roof)
  const TopSurface top(pts, 1.0);
  EXPECT_FLOAT_EQ(top.Query(4.5f, 5.5f).occluder, 8.0f);  // roof east, 8 m west: the lower of the pair
  EXPECT_FLOAT_EQ(top.Query(3.5f, 5.5f).occluder, 8.0f);  // own cell holds the canopy
  EXPECT_FLOAT_EQ(top.Query(2.5f, 5.5f).occluder, 0.0f);  // canopy on one side only
}

TEST(TopSurfaceTest, RefusesHugeGrids) {
  std::vector<Eigen::Vector3f> pts = {{0, 0, 0}, {1e5f, 1e5f, 0}};
  EXPECT_THROW(TopSurface(pts, 0.1), Error);
}

}  // namespace
}  // namespace sacfuse
