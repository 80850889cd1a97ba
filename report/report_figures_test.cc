// Pictures of the run report on hand-made inputs: view colours, the source-view map with hill-shading, the
// cross-section panels, and the figures' JSON record.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "report/report_colours.h"
#include "report/report_figures.h"
#include "report/report_map_figure.h"
#include "report/report_profile_figure.h"

namespace sacfuse {
namespace {

// Hue in [0, 1) of an 8-bit colour.
double Hue(const Rgb& c) {
  const double r = c[0] / 255.0, g = c[1] / 255.0, b = c[2] / 255.0;
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), d = mx - mn;
  if (d <= 0) return 0;
  double h = mx == r ? std::fmod((g - b) / d, 6.0) : mx == g ? (b - r) / d + 2 : (r - g) / d + 4;
  h /= 6.0;
  return h < 0 ? h + 1 : h;
}

TEST(ReportColoursTest, NamesTellNadirFromOblique) {
  EXPECT_EQ(ClassifyViewName("nadir/0012.jpg"), ViewKind::kNadir);
  EXPECT_EQ(ClassifyViewName("Oblique_Left/0003.jpg"), ViewKind::kOblique);
  EXPECT_EQ(ClassifyViewName("obl_fwd_7.tif"), ViewKind::kOblique);
  EXPECT_EQ(ClassifyViewName("IMG_0001.JPG"), ViewKind::kUnknown);
  EXPECT_TRUE(ViewKindsKnown({ViewKind::kNadir, ViewKind::kOblique}));
  EXPECT_FALSE(ViewKindsKnown({ViewKind::kNadir, ViewKind::kUnknown}));
}

TEST(ReportColoursTest, ColoursAreDistinctAndGroupedByKind) {
  std::vector<ViewKind> kinds;
  for (int i = 0; i < 16; ++i) kinds.push_back(ViewKind::kNadir);
  for (int i = 0; i < 43; ++i) kinds.push_back(ViewKind::kOblique);
  const std::vector<Rgb> colours = ViewColours(kinds);
  ASSERT_EQ(colours.size(), 59u);
  EXPECT_EQ(std::set<Rgb>(colours.begin(), colours.end()).size(), 59u);
  for (size_t i = 0; i < colours.size(); ++i) {
    const double h = Hue(colours[i]);
    if (i < 16) {
      EXPECT_GT(h, 0.45) << i;  // cyan .. violet
      EXPECT_LT(h, 0.82) << i;
    } else {
      EXPECT_TRUE(h < 0.32 || h > 0.95) << i << " hue " << h;  // red .. yellow-green
    }
  }
  // Unknown kinds: all distinct too.
  const std::vector<Rgb> plain = ViewColours(std::vector<ViewKind>(40, ViewKind::kUnknown));
  EXPECT_EQ(std::set<Rgb>(plain.begin(), plain.end()).size(), 40u);
}

TEST(ReportMapFigureTest, CellsTakeTheColourOfTheirTopmostPointsView) {
  TopGrid g(0.0, 3.0, 1.0, 3, 3);
  // A flat surface at z = 5 everywhere (no shading), view 1 (ID 1) on the west column, view 2 elsewhere; view 1's
  // lower points under view 2 do not show.
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      g.Add(c + 0.5, 2.5 - r, 5.0, c == 0 ? 1 : 2);
      if (c > 0) g.Add(c + 0.5, 2.5 - r, 4.0, 1);
    }
  }
  g.top_z[g.Index(1, 1)] = NAN;  // the centre cell empty
  g.source_id[g.Index(1, 1)] = 0;
  const std::vector<Rgb> colours = {{200, 10, 10}, {10, 10, 200}};
  SourceMapStyle style;
  style.pixels_per_cell = 2;
  const RgbImage img = RenderSourceMap(g, colours, style);
  ASSERT_EQ(img.width, 6);
  ASSERT_EQ(img.height, 6);
  const auto px = [&](int row, int col) { return Rgb{img.at(row, col, 0), img.at(row, col, 1), img.at(row, col, 2)}; };
  EXPECT_EQ(px(0, 0), colours[0]);   // cell (0, 0): view 1
  EXPECT_EQ(px(5, 1), colours[0]);   // cell (2, 0)
  EXPECT_EQ(px(0, 5), colours[1]);   // cell (0, 2): view 2 (its point is the top one)
  EXPECT_EQ(px(3, 3), style.empty);  // the empty centre
}

TEST(ReportMapFigureTest, HillShadeIsOneOnFlatGroundBrighterFacingTheSun) {
  // A ramp rising to the east (surface faces west) and one rising to the west (faces east); sun from the NW.
  TopGrid east(0, 5, 1, 5, 5), west(0, 5, 1, 5, 5), flat(0, 5, 1, 5, 5);
  for (int r = 0; r < 5; ++r) {
    for (int c = 0; c < 5; ++c) {
      east.Add(c + 0.5, 4.5 - r, 1.0 * c, 1);
      west.Add(c + 0.5, 4.5 - r, -1.0 * c, 1);
      flat.Add(c + 0.5, 4.5 - r, 3.0, 1);
    }
  }
  const SourceMapStyle style;
  EXPECT_FLOAT_EQ(HillShade(flat, style)[flat.Index(2, 2)], 1.0f);
  EXPECT_GT(HillShade(east, style)[east.Index(2, 2)], 1.0f);  // faces west, towards the NW sun
  EXPECT_LT(HillShade(west, style)[west.Index(2, 2)], 1.0f);
}

TEST(ReportProfileFigureTest, PointsLandInTheirPixelsAndTheReferenceIsOnTop) {
  PlotFrame f;
  f.s_min = 0;
  f.s_max = 100;
  f.z_min = 0;
  f.z_max = 50;
  f.width_px = 200;
  f.height_px = 100;  // 2 px per metre both ways
  EXPECT_DOUBLE_EQ(f.VerticalExaggeration(), 1.0);
  const std::vector<Rgb> colours = {{255, 0, 0}, {0, 0, 255}};
  ProfileStyle style;
  style.alpha = 1.0;
  style.dot_px = 1;
  style.reference_dot_px = 1;
  const std::vector<ProfilePoint> points = {{10.25f, 40.25f, 1}, {50.25f, 10.25f, 2}, {150.0f, 10.0f, 1}};
  const std::vector<ProfilePoint> reference = {{50.25f, 10.25f, 0}};
  const RgbImage img = RenderProfilePanel(points, reference, colours, f, {}, style);
  // (10.25, 40.25): column 20, row (50 - 40.25) * 2 = 19.5 -> 19.
  EXPECT_EQ(img.at(19, 20, 0), 255);
  EXPECT_EQ(img.at(19, 20, 2), 0);
  // (50.25, 10.25): column 100, row 79 — covered by the reference (black).
  EXPECT_EQ(img.at(79, 100, 0), 0);
  EXPECT_EQ(img.at(79, 100, 2), 0);
  // Elsewhere white; the point beyond the frame is not drawn.
  size_t coloured = 0;
  for (size_t i = 0; i < img.data.size(); i += 3) coloured += img.data[i] != 255 || img.data[i + 2] != 255;
  EXPECT_EQ(coloured, 2u);
}

TEST(ReportProfileFigureTest, FrameKeepsTrueShapeWithinLimits) {
  const PlotFrame f = MakePlotFrame(100.0, 0.0, 30.0, 1000, 300, 100, 400);
  EXPECT_EQ(f.width_px, 1000);
  EXPECT_EQ(f.height_px, 300);
  EXPECT_NEAR(f.VerticalExaggeration(), 1.0, 1e-12);
  // Flat: the minimum height, exaggerated 5x.
  const PlotFrame flat = MakePlotFrame(100.0, 0.0, 2.0, 1000, 300, 100, 400);
  EXPECT_EQ(flat.height_px, 100);
  EXPECT_NEAR(flat.VerticalExaggeration(), 5.0, 1e-12);
  // Tall: the maximum height and a narrower panel, still true shape.
  const PlotFrame tall = MakePlotFrame(40.0, 0.0, 40.0, 1000, 300, 100, 400);
  EXPECT_EQ(tall.height_px, 400);
  EXPECT_EQ(tall.width_px, 400);
  EXPECT_NEAR(tall.VerticalExaggeration(), 1.0, 1e-12);
  // Very tall: squashed at the minimum width.
  const PlotFrame tower = MakePlotFrame(10.0, 0.0, 40.0, 1000, 300, 100, 400);
  EXPECT_EQ(tower.width_px, 300);
  EXPECT_NEAR(tower.VerticalExaggeration(), (400.0 / 40.0) / (300.0 / 10.0), 1e-12);
}

TEST(ReportProfileFigureTest, RobustRangeIgnoresAFewBlunders) {
  std::vector<ProfilePoint> pts;
  for (int i = 0; i < 1000; ++i) pts.push_back({0.0f, 100.0f + (i % 20), 1});
  pts.push_back({0.0f, -500.0f, 1});
  pts.push_back({0.0f, 900.0f, 1});
  double lo = 0, hi = 0;
  RobustHeightRange({&pts}, &lo, &hi);
  EXPECT_NEAR(lo, 99.0, 1e-6);   // 100 - 1 m pad
  EXPECT_NEAR(hi, 120.0, 1e-6);  // 119 + 1 m pad
}

TEST(ReportFiguresJsonTest, RoundTrips) {
  ReportFigures f;
  f.map.present = true;
  f.map.file = "map.png";
  f.map.width_px = 800;
  f.map.height_px = 600;
  f.map.x_min = 412345.5;
  f.map.y_max = 5712345.25;
  f.map.metres_per_px = 0.125;
  f.profile.present = true;
  f.profile.strip.start_xy = {1.5, 2.5};
  f.profile.strip.end_xy = {1.5, 62.5};
  f.profile.strip.half_width_m = 0.2;
  f.profile.frame = MakePlotFrame(60.0, 95.0, 130.0, 1000, 300, 150, 380);
  f.profile.after_drawn = 1234;
  f.profile.after_source = "3 tile files";
  f.seconds = 2.5;
  const ReportFigures g = ReportFiguresFromJson(ReportFiguresToJson(f));
  EXPECT_EQ(g.map.file, "map.png");
  EXPECT_DOUBLE_EQ(g.map.x_min, 412345.5);
  EXPECT_DOUBLE_EQ(g.map.y_max, 5712345.25);
  EXPECT_DOUBLE_EQ(g.profile.strip.end_xy.y(), 62.5);
  EXPECT_EQ(g.profile.frame.height_px, f.profile.frame.height_px);
  EXPECT_EQ(g.profile.after_drawn, 1234u);
  EXPECT_EQ(g.profile.after_source, "3 tile files");
  EXPECT_THROW(ReportFiguresFromJson("{\"map\": 3}"), std::exception);
}

}  // namespace
}  // namespace sacfuse
