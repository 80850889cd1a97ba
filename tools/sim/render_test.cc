#include "tools/sim/render.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/backproject.h"
#include "tools/sim/city_layout.h"
#include "tools/sim/city_scene.h"
#include "tools/sim/flight_plan.h"
#include "tools/sim/simple_scenes.h"

namespace sacfuse::sim {
namespace {

constexpr double kGround = 100.0;
constexpr double kHeight = 120.0;  // camera above ground

Rigid3d PoseAt(const Eigen::Vector3d& center, const Eigen::Vector2d& toward, double tilt_deg) {
  const Rigid3d world_from_cam{Eigen::Quaterniond(WorldFromCameraRotation(toward, tilt_deg * M_PI / 180.0)), center};
  return world_from_cam.Inverse();
}

RenderedView Render(const Surface& s, const PinholeCamera& cam, const Rigid3d& pose, int ds = 1) {
  RenderRequest r;
  r.surface = &s;
  r.camera = cam;
  r.cam_from_world = pose;
  r.depth_width = cam.width / ds;
  r.depth_height = cam.height / ds;
  return RenderView(r);
}

TEST(RenderTest, FlatPlaneNadirDepthIsFlyingHeight) {
  const BoxScene plane(kGround);
  const PinholeCamera cam = PinholeCamera::Centered(160, 120, 500.0);
  const RenderedView rv = Render(plane, cam, PoseAt({500.3, 200.7, kGround + kHeight}, {0, 1}, 0.0));
  ASSERT_EQ(rv.depth.width, 160);
  double worst = 0.0;
  for (float d : rv.depth.data) worst = std::max(worst, std::abs(d - kHeight));
  EXPECT_LT(worst, 1e-4);  // every pixel, float precision
  ASSERT_EQ(rv.image.width, 160);
  int dark = 0;
  for (size_t i = 0; i < rv.image.num_pixels(); ++i) dark += rv.image.data[3 * i] < 10 ? 1 : 0;
  EXPECT_EQ(dark, 0);  // every pixel shaded
}

TEST(RenderTest, DownsampledDepthIsExactToo) {
  const BoxScene plane(kGround);
  const PinholeCamera cam = PinholeCamera::Centered(160, 120, 500.0);
  const RenderedView rv = Render(plane, cam, PoseAt({0.0, 0.0, kGround + kHeight}, {1, 0}, 30.0), 2);
  ASSERT_EQ(rv.depth.width, 80);
  ASSERT_EQ(rv.depth.height, 60);
  const PinholeCamera dc = cam.Scaled(80, 60);
  const Rigid3d world_from_cam = PoseAt({0.0, 0.0, kGround + kHeight}, {1, 0}, 30.0).Inverse();
  for (int row = 0; row < 60; ++row) {
    for (int col = 0; col < 80; ++col) {
      const Eigen::Vector3d p = DepthPixelToWorld(dc, world_from_cam, col, row, rv.depth.at(row, col));
      ASSERT_NEAR(p.z(), kGround, 2e-3) << row << " " << col;
    }
  }
}

TEST(RenderTest, BoxRoofDepthAndWallsInObliques) {
  const double h = 15.0;
  const BoxScene scene(kGround, Box2d{-10.0, -8.0, 10.0, 8.0}, h);
  const PinholeCamera cam = PinholeCamera::Centered(200, 150, 600.0);
  const RenderedView nadir = Render(scene, cam, PoseAt({0.0, 0.0, kGround + kHeight}, {0, 1}, 0.0));
  // The roof centre projects to the principal point: pixels (74..75, 99..100) around it.
  EXPECT_NEAR(nadir.depth.at(75, 100), kHeight - h, 1e-4);
  EXPECT_NEAR(nadir.depth.at(74, 99), kHeight - h, 1e-4);
  EXPECT_NEAR(nadir.depth.at(2, 2), kHeight, 1e-4);  // ground in the corner

  // An oblique looking east at the west wall sees pixels that are neither roof nor ground.
  const Rigid3d pose = PoseAt({-60.0, 0.0, kGround + 60.0}, {1, 0}, 45.0);
  const RenderedView obl = Render(scene, cam, pose);
  const Rigid3d world_from_cam = pose.Inverse();
  int wall = 0;
  for (int row = 0; row < cam.height; ++row) {
    for (int col = 0; col < cam.width; ++col) {
      const float d = obl.depth.at(row, col);
      ASSERT_GT(d, 0.0f);
      const Eigen::Vector3d p = DepthPixelToWorld(cam, world_from_cam, col, row, d);
      if (p.z() > kGround + 1.0 && p.z() < kGround + h - 1.0) {
        ++wall;
        EXPECT_NEAR(p.x(), -10.0, 0.3);  // on the west wall
      }
    }
  }
  EXPECT_GT(wall, 500);
}

// With no errors, back-projecting every depth pixel lands on the true surface except within one sample of a
// height jump (walls) or a crease (ridges, canopy rims).
TEST(RenderTest, CityDepthLiesOnTheTrueSurface) {
  CityParams p;
  p.area_width_m = p.area_height_m = 60.0;
  p.center_x = 390030.0;
  p.center_y = 5705030.0;
  p.ground_z = kGround;
  p.seed = 3;
  const CityScene city(GenerateCityLayout(p));
  const PinholeCamera cam = PinholeCamera::Centered(320, 240, 600.0);
  const Eigen::Vector3d c(p.center_x, p.center_y, kGround + 100.0);
  struct Case {
    Eigen::Vector3d center;
    Eigen::Vector2d toward;
    double tilt;
  };
  for (const Case& k : {Case{c, {0, 1}, 0.0}, Case{c - Eigen::Vector3d(60, 0, 0), {1, 0}, 40.0}}) {
    const Rigid3d pose = PoseAt(k.center, k.toward, k.tilt);
    const RenderedView rv = Render(city, cam, pose);
    const Rigid3d world_from_cam = pose.Inverse();
    int tested = 0, bad = 0;
    double worst = 0.0;
    for (int row = 0; row < cam.height; ++row) {
      for (int col = 0; col < cam.width; ++col) {
        const Eigen::Vector3d q = DepthPixelToWorld(cam, world_from_cam, col, row, rv.depth.at(row, col));
        // Locally planar within +-0.25 m (four times the sample spacing): second differences vanish.
        const double e = 0.25, z0 = city.Height(q.x(), q.y());
        const double dxx = city.Height(q.x() + e, q.y()) + city.Height(q.x() - e, q.y()) - 2 * z0;
        const double dyy = city.Height(q.x(), q.y() + e) + city.Height(q.x(), q.y() - e) - 2 * z0;
        const double dxy = city.Height(q.x() + e, q.y() + e) + city.Height(q.x() - e, q.y() - e) - 2 * z0;
        const double dyx = city.Height(q.x() + e, q.y() - e) + city.Height(q.x() - e, q.y() + e) - 2 * z0;
        if (std::max({std::abs(dxx), std::abs(dyy), std::abs(dxy), std::abs(dyx)}) > 0.01) continue;
        ++tested;
        const double err = std::abs(q.z() - z0);
        worst = std::max(worst, err);
        bad += err >= 0.02 ? 1 : 0;
      }
    }
    EXPECT_GT(tested, cam.width * cam.height / 2) << "tilt " << k.tilt;
    EXPECT_EQ(bad, 0) << "tilt " << k.tilt << ": worst " << worst;
  }
}

TEST(RenderTest, PowerOfTwoSpacing) {
  EXPECT_DOUBLE_EQ(NearestPowerOfTwo(0.05), 0.0625);
  EXPECT_DOUBLE_EQ(NearestPowerOfTwo(1.0), 1.0);
  EXPECT_DOUBLE_EQ(NearestPowerOfTwo(0.3), 0.25);
}

}  // namespace
}  // namespace sacfuse::sim
