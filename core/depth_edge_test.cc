// Foreground depth edges (core/depth_edge.h) on a hand-made depth map: a roof 10 m in front of the ground, with a
// band of invalid pixels between them as a left-right check leaves it.
#include "core/depth_edge.h"

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

// 40 x 20 pixels: ground at 100 m; a roof at 90 m over columns 10-19; columns 20-22 invalid; ground beyond.
DepthMap RoofOverGround() {
  DepthMap depth(40, 20, 1, 100.0f);
  for (int r = 0; r < depth.height; ++r) {
    for (int c = 10; c < 20; ++c) depth.at(r, c) = 90.0f;
    for (int c = 20; c < 23; ++c) depth.at(r, c) = 0.0f;
  }
  return depth;
}

TEST(DepthEdgeTest, TheRoofsOuterBandIsAnEdgeItsInsideAndTheGroundAreNot) {
  const DepthMap depth = RoofOverGround();
  const double jump_m = 5.0;
  // West side: the ground is next to the roof.
  EXPECT_TRUE(OnForegroundEdge(depth, 10, 10, 90.0, jump_m, 2));
  EXPECT_TRUE(OnForegroundEdge(depth, 10, 11, 90.0, jump_m, 2));
  EXPECT_FALSE(OnForegroundEdge(depth, 10, 12, 90.0, jump_m, 2));
  // East side: the ground lies beyond 3 invalid pixels, within the reach.
  EXPECT_TRUE(OnForegroundEdge(depth, 10, 19, 90.0, jump_m, 2));
  EXPECT_TRUE(OnForegroundEdge(depth, 10, 18, 90.0, jump_m, 2));
  EXPECT_FALSE(OnForegroundEdge(depth, 10, 17, 90.0, jump_m, 2));
  EXPECT_TRUE(OnForegroundEdge(depth, 10, 17, 90.0, jump_m, 3));
  // The ground next to the roof is the deeper side, not a foreground.
  EXPECT_FALSE(OnForegroundEdge(depth, 10, 9, 100.0, jump_m, 2));
  EXPECT_FALSE(OnForegroundEdge(depth, 10, 23, 100.0, jump_m, 2));
  // A jump smaller than jump_m is no edge; band 0 is none.
  EXPECT_FALSE(OnForegroundEdge(depth, 10, 10, 90.0, 12.0, 2));
  EXPECT_FALSE(OnForegroundEdge(depth, 10, 10, 90.0, jump_m, 0));
}

TEST(DepthEdgeTest, HolesWithoutADeeperSurfaceAndTheImageBorderAreNoEdge) {
  DepthMap depth(30, 30, 1, 50.0f);
  for (int r = 10; r < 13; ++r) {
    for (int c = 10; c < 13; ++c) depth.at(r, c) = 0.0f;  // a hole in a flat surface
  }
  EXPECT_FALSE(OnForegroundEdge(depth, 9, 9, 50.0, 5.0, 2));
  EXPECT_FALSE(OnForegroundEdge(depth, 0, 0, 50.0, 5.0, 2));
  // A deeper surface 7 pixels away (the reach) behind the hole makes the hole's rim an edge; 8 pixels away not.
  depth.at(11, 16) = 80.0f;
  EXPECT_TRUE(OnForegroundEdge(depth, 9, 9, 50.0, 5.0, 2));
  depth.at(11, 16) = 50.0f;
  depth.at(11, 17) = 80.0f;
  EXPECT_FALSE(OnForegroundEdge(depth, 9, 9, 50.0, 5.0, 2));
}

TEST(DepthEdgeTest, SquareAroundIsClippedToTheRaster) {
  EXPECT_EQ(SquareAround(5, 6, 2, 20, 10), (PixelWindow{3, 8, 4, 9}));
  EXPECT_EQ(SquareAround(0, 19, 3, 20, 10), (PixelWindow{0, 4, 16, 20}));
  EXPECT_EQ(SquareAround(9, 0, 0, 20, 10), (PixelWindow{9, 10, 0, 1}));
}

TEST(DepthEdgeTest, AnyDepthInWindowIsClippedToTheRaster) {
  DepthMap depth(5, 4, 1, 1.0f);
  depth.at(3, 4) = 2.0f;
  auto is_two = [](float q) { return q == 2.0f; };
  EXPECT_TRUE(AnyDepthInWindow(depth, 2, 3, 1, is_two));
  EXPECT_FALSE(AnyDepthInWindow(depth, 1, 2, 1, is_two));
  EXPECT_TRUE(AnyDepthInWindow(depth, 0, 0, 10, is_two));
  EXPECT_FALSE(AnyDepthInWindow(depth, 3, 4, 0, [](float q) { return q == 1.0f; }));
}

}  // namespace
}  // namespace sacfuse
