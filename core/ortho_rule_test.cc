// The true orthophoto's view rule (core/ortho_rule.h) on a hand-made scene with known answers: a 10 m tall wall on
// a flat ground, two nadir-looking views on either side of it.
#include "core/ortho_rule.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

constexpr double kCell = 0.5;

// A down-looking camera at `centre` (camera x = world x, camera y = -world y, optical axis = world -z).
OrthoView DownView(uint32_t index, const Eigen::Vector3d& centre) {
  Rigid3d cam_from_world;
  Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
  r(0, 0) = 1;
  r(1, 1) = -1;
  r(2, 2) = -1;
  cam_from_world.rotation = Eigen::Quaterniond(r);
  cam_from_world.translation = -(r * centre);
  return OrthoViewOf(index, PinholeCamera::Centered(1000, 1000, 200.0), cam_from_world);
}

// 40 x 40 cells of 0.5 m from (0, 0): ground at z = 0, a wall 10 m tall over x in [10, 12) (columns 20-23).
DsmPatch WallScene() {
  CellWindow w;
  w.cell_m = kCell;
  w.cols = 40;
  w.rows = 40;
  std::vector<float> z(w.size(), 0.0f);
  for (int64_t row = 0; row < w.rows; ++row) {
    for (int64_t col = 20; col < 24; ++col) z[w.Index(col, row)] = 10.0f;
  }
  return MakeDsmPatch(w, std::move(z));
}

TEST(OrthoRuleTest, AnOccludedSelectedViewGivesWayToTheViewThatSeesTheCell) {
  const DsmPatch dsm = WallScene();
  const OrthoRule rule = OrthoRuleForCell(kCell);
  // Ground cell (16, 20): x = 8.25, y = 10.25. View 0 east of the wall (its ray crosses the wall at z < 2 m), view 1
  // west of the cell.
  const std::vector<OrthoView> views = {DownView(0, {30, 10.25, 20}), DownView(1, {0, 10.25, 20})};
  const Eigen::Vector3d x = CellPoint(16, 20, kCell, 0.0);
  EXPECT_FALSE(RayClearOfDsm(x, views[0].centre, dsm, rule));
  EXPECT_TRUE(RayClearOfDsm(x, views[1].centre, dsm, rule));

  CellWindow inner = dsm.window;
  inner.col0 = 16;
  inner.row0 = 20;
  inner.cols = 1;
  inner.rows = 1;
  EXPECT_EQ(OrthoCellViews(dsm, inner, {0}, views, rule), std::vector<int32_t>{1});  // selected 0 is occluded
  EXPECT_EQ(OrthoCellViews(dsm, inner, {1}, views, rule), std::vector<int32_t>{1});
  // At the wall's west foot (19, 20), view 0 (east, beyond the wall) is hidden and view 1 sees it; a cell at a wall
  // takes the most nadir view that sees it whatever was selected: view 2 straight above.
  inner.col0 = 19;
  const std::vector<OrthoView> three = {views[0], views[1], DownView(2, {9.75, 10.25, 20})};
  EXPECT_EQ(OrthoCellViews(dsm, inner, {1}, three, rule), std::vector<int32_t>{2});
  // A roof cell (21, 20) is seen by both: the selected view keeps it.
  inner.col0 = 21;
  EXPECT_EQ(OrthoCellViews(dsm, inner, {0}, views, rule), std::vector<int32_t>{0});
  EXPECT_EQ(OrthoCellViews(dsm, inner, {1}, views, rule), std::vector<int32_t>{1});
}

TEST(OrthoRuleTest, WithoutASelectedViewTheMostNadirViewThatSeesTheCellIsTaken) {
  const DsmPatch dsm = WallScene();
  const OrthoRule rule = OrthoRuleForCell(kCell);
  // Ground cell (30, 20): x = 15.25. View 0 at x = 14 (nearly nadir), view 1 at x = 30 (more oblique), view 2 at
  // x = 0 behind the wall (its ray is blocked).
  const std::vector<OrthoView> views = {DownView(0, {14, 10.25, 20}), DownView(1, {30, 10.25, 20}),
                                        DownView(2, {0, 10.25, 20})};
  CellWindow inner = dsm.window;
  inner.col0 = 30;
  inner.row0 = 20;
  inner.cols = 1;
  inner.rows = 1;
  EXPECT_EQ(OrthoCellViews(dsm, inner, {-1}, views, rule), std::vector<int32_t>{0});
  EXPECT_EQ(OrthoCellViews(dsm, inner, {2}, views, rule), std::vector<int32_t>{0});  // 2 is occluded
  // Ground cell (25, 20) right at the wall's east foot, x = 12.75: view 2's ray hits the wall, view 0 (x = 14) sees
  // it; without view 0 the oblique view 1 does; with only view 2 nothing does (transparent).
  inner.col0 = 25;
  EXPECT_EQ(OrthoCellViews(dsm, inner, {-1}, views, rule), std::vector<int32_t>{0});
  const std::vector<OrthoView> without_0 = {DownView(0, {0, 10.25, 20}), DownView(1, {30, 10.25, 20})};
  EXPECT_EQ(OrthoCellViews(dsm, inner, {0}, without_0, rule), std::vector<int32_t>{1});
  std::vector<OrthoView> only_west = {DownView(0, {0, 10.25, 20})};
  EXPECT_EQ(OrthoCellViews(dsm, inner, {0}, only_west, rule), std::vector<int32_t>{-1});
  // A cell without a DSM height gets no view.
  DsmPatch holed = dsm;
  holed.z[holed.window.Index(25, 20)] = NAN;
  EXPECT_EQ(OrthoCellViews(holed, inner, {0}, views, rule), std::vector<int32_t>{-1});
}

TEST(OrthoRuleTest, ACellOutsideEveryImageGetsNoView) {
  const DsmPatch dsm = WallScene();
  // 1000 px at f = 200 px from 20 m: the image covers +-50 m; a view 100 m away does not see the cell.
  const std::vector<OrthoView> views = {DownView(0, {120, 10.25, 20})};
  CellWindow inner = dsm.window;
  inner.col0 = 30;
  inner.row0 = 20;
  inner.cols = 1;
  inner.rows = 1;
  EXPECT_EQ(OrthoCellViews(dsm, inner, {0}, views, OrthoRuleForCell(kCell)), std::vector<int32_t>{-1});
}

TEST(OrthoRuleTest, BilinearSamplingInterpolatesBetweenPixelCentres) {
  RgbImage image(2, 2, 3, 0);
  image.at(0, 0, 0) = 0;
  image.at(0, 1, 0) = 100;
  image.at(1, 0, 0) = 200;
  image.at(1, 1, 0) = 100;
  image.at(1, 1, 2) = 40;
  EXPECT_EQ(SampleBilinear(image, 0.5, 0.5)[0], 0);     // the centre of pixel (0, 0)
  EXPECT_EQ(SampleBilinear(image, 1.0, 0.5)[0], 50);    // half way to (0, 1)
  EXPECT_EQ(SampleBilinear(image, 1.0, 1.0)[0], 100);   // the mean of the four
  EXPECT_EQ(SampleBilinear(image, 1.0, 1.0)[2], 10);
  EXPECT_EQ(SampleBilinear(image, 0.0, 2.0)[0], 200);   // clamped at the border
}

TEST(OrthoRuleTest, ACellsColourAveragesSamplesOverItsArea) {
  // A nadir view 10 m above the plane z = 0 at f = 100 px: 10 cm per pixel; image centre (50, 50) below (0, 0).
  const OrthoView view = DownView(0, {0, 0, 10});
  const PinholeCamera camera = PinholeCamera::Centered(100, 100, 100.0);
  RgbImage image(100, 100, 3, 0);
  for (int r = 0; r < 100; ++r) {
    for (int c = 50; c < 100; ++c) image.at(r, c, 0) = 200;  // x >= 0 is red
  }
  // A 1 m cell centred on x = 0 straddles the edge: 10 cm pixels, so 8 x 8 samples, half of them each side.
  EXPECT_EQ(CellColour(image, camera, view.cam_from_world, {0.0, 0.0, 0.0}, 1.0)[0], 100);
  // A cell centred on x = 2 m lies wholly in the red half.
  EXPECT_EQ(CellColour(image, camera, view.cam_from_world, {2.0, 0.0, 0.0}, 1.0)[0], 200);
  EXPECT_EQ(CellColour(image, camera, view.cam_from_world, {-2.0, 0.0, 0.0}, 1.0)[0], 0);
}

}  // namespace
}  // namespace sacfuse
