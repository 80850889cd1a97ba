#include "tiling/tile_windows.h"

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

// Nadir camera 100 m above the origin: x_cam = X, y_cam = -Y, z_cam = 100 - Z; 1000 x 1000 px, f = 1000 px.
View NadirView() {
  View v;
  v.camera = PinholeCamera::Centered(1000, 1000, 1000.0);
  v.cam_from_world.rotation = Eigen::Quaterniond(0, 1, 0, 0);
  v.cam_from_world.translation = Eigen::Vector3d(0, 0, 100);
  return v;
}

Box2d Box(double x0, double y0, double x1, double y1) {
  Box2d b;
  b.Extend(Eigen::Vector2d(x0, y0));
  b.Extend(Eigen::Vector2d(x1, y1));
  return b;
}

TEST(TileWindowsTest, NadirWindowMatchesHandComputation) {
  // Depth raster 500 x 500: f = 500, c = 250. u = 500 X / (100 - Z) + 250, v = -500 Y / (100 - Z) + 250.
  // X in [-10, 10], Z in [0, 20]: u in [187.5, 312.5]; Y in [0, 20]: v in [125, 250].
  const auto w = ViewWindowForBox(NadirView(), 500, 500, Box(-10, 0, 10, 20), 0.0, 20.0, 2);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->col_begin, 185);
  EXPECT_EQ(w->col_end, 315);
  EXPECT_EQ(w->row_begin, 123);
  EXPECT_EQ(w->row_end, 252);
  EXPECT_EQ(w->num_pixels(), 130u * 129u);
}

TEST(TileWindowsTest, WindowIsClippedToTheRaster) {
  // X in [-100, 0] at Z = 0: u in [-250, 250] -> cols [0, 250 + 3).
  const auto w = ViewWindowForBox(NadirView(), 500, 500, Box(-100, -1, 0, 1), 0.0, 0.0, 3);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->col_begin, 0);
  EXPECT_EQ(w->col_end, 253);
  EXPECT_EQ(w->row_begin, 242);  // v in [245, 255]
  EXPECT_EQ(w->row_end, 258);
}

TEST(TileWindowsTest, BoxOutsideTheViewOrBehindItIsNotSeen) {
  EXPECT_FALSE(ViewWindowForBox(NadirView(), 500, 500, Box(1000, 0, 1010, 10), 0.0, 20.0, 2).has_value());
  EXPECT_FALSE(ViewWindowForBox(NadirView(), 500, 500, Box(-10, -10, 10, 10), 200.0, 300.0, 2).has_value());
  // Straddling the camera plane: conservative, the whole raster.
  const auto w = ViewWindowForBox(NadirView(), 500, 500, Box(-10, -10, 10, 10), 0.0, 300.0, 2);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(*w, (PixelWindow{0, 500, 0, 500}));
}

TEST(TileWindowsTest, WindowCameraProjectsLikeTheFullRasterShifted) {
  const View view = NadirView();
  const PinholeCamera full = view.camera.Scaled(500, 500);
  const PixelWindow w{123, 252, 185, 315};
  const PinholeCamera win = WindowCamera(full, w);
  EXPECT_EQ(win.width, 130);
  EXPECT_EQ(win.height, 129);
  const Eigen::Vector3d p = view.cam_from_world * Eigen::Vector3d(3, 7, 12);
  EXPECT_NEAR(win.Project(p).x(), full.Project(p).x() - 185, 1e-9);
  EXPECT_NEAR(win.Project(p).y(), full.Project(p).y() - 123, 1e-9);
}

}  // namespace
}  // namespace sacfuse
