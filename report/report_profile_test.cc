// The cross-section strip: local minimum filter, the strip rule on synthetic buildings, the point test, sampling.
#include "report/report_profile.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

// Flat ground at z = 100 over 100 m x 100 m (cells of 0.5 m, western edge x = 0, northern edge y = 100).
TopGrid Ground() {
  TopGrid g(0.0, 100.0, 0.5, 200, 200);
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) g.Add(g.CellCenterX(c), g.CellCenterY(r), 100.0, 1);
  }
  return g;
}

void Box(TopGrid* g, double x0, double x1, double y0, double y1, double z, uint16_t id) {
  for (int r = 0; r < g->height; ++r) {
    for (int c = 0; c < g->width; ++c) {
      const double x = g->CellCenterX(c), y = g->CellCenterY(r);
      if (x >= x0 && x <= x1 && y >= y0 && y <= y1) g->Add(x, y, z, id);
    }
  }
}

TEST(ReportProfileTest, LocalMinimumEqualsBruteForce) {
  TopGrid g(0.0, 20.0, 1.0, 23, 17);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> z(0.0f, 50.0f);
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      if ((r * 7 + c * 3) % 5 != 0) g.Add(g.CellCenterX(c), g.CellCenterY(r), z(rng), 1);  // some cells empty
    }
  }
  for (const int radius : {0, 1, 3, 30}) {
    const std::vector<float> fast = LocalMinimum(g, radius);
    for (int r = 0; r < g.height; ++r) {
      for (int c = 0; c < g.width; ++c) {
        float best = INFINITY;
        for (int rr = std::max(0, r - radius); rr <= std::min(g.height - 1, r + radius); ++rr) {
          for (int cc = std::max(0, c - radius); cc <= std::min(g.width - 1, c + radius); ++cc) {
            if (!g.Empty(rr, cc)) best = std::min(best, g.top_z[g.Index(rr, cc)]);
          }
        }
        const float got = fast[g.Index(r, c)];
        if (std::isinf(best)) {
          EXPECT_TRUE(std::isnan(got));
        } else {
          EXPECT_EQ(got, best) << "radius " << radius << " cell " << r << "," << c;
        }
      }
    }
  }
}

TEST(ReportProfileTest, StripCrossesTheBuildingTheShortWayWithGroundOnBothSides) {
  TopGrid g = Ground();
  Box(&g, 30.0, 60.0, 40.0, 52.0, 118.0, 2);  // 30 m (x) by 12 m (y), 18 m high, flat roof
  // A tree: higher than the roof but a spiky crown (not flat), so it is not picked.
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      const double dx = g.CellCenterX(c) - 80.0, dy = g.CellCenterY(r) - 80.0;
      const double d = std::hypot(dx, dy);
      if (d < 3.0) g.Add(g.CellCenterX(c), g.CellCenterY(r), 125.0 - 3.0 * d + ((r + c) % 2) * 2.0, 3);
    }
  }
  const auto strip = PickProfileStrip(g, StripPickOptions{});
  ASSERT_TRUE(strip.has_value());
  EXPECT_NEAR(strip->relief_m, 18.0, 1e-4);
  // Through the building.
  EXPECT_GE(strip->peak_xy.x(), 30.0);
  EXPECT_LE(strip->peak_xy.x(), 60.0);
  EXPECT_GE(strip->peak_xy.y(), 40.0);
  EXPECT_LE(strip->peak_xy.y(), 52.0);
  // Along y (the 12 m side), extending at least margin_m (10 m) beyond both edges.
  EXPECT_DOUBLE_EQ(strip->start_xy.x(), strip->end_xy.x());
  EXPECT_LE(strip->start_xy.y(), 40.0 - 10.0 + 1e-9);
  EXPECT_GE(strip->end_xy.y(), 52.0 + 10.0 - 1e-9);
  EXPECT_LE(strip->Length(), StripPickOptions{}.max_length_m);
  // Its height range holds the ground and the roof.
  EXPECT_LT(strip->z_min_m, 100.0);
  EXPECT_GT(strip->z_max_m, 118.0);
}

TEST(ReportProfileTest, StripRunsAlongXForABuildingNarrowInX) {
  TopGrid g = Ground();
  Box(&g, 45.0, 53.0, 20.0, 70.0, 110.0, 2);  // 8 m (x) by 50 m (y)
  const auto strip = PickProfileStrip(g, StripPickOptions{});
  ASSERT_TRUE(strip.has_value());
  EXPECT_DOUBLE_EQ(strip->start_xy.y(), strip->end_xy.y());
  EXPECT_LT(strip->start_xy.x(), 45.0 - 9.99);
  EXPECT_GT(strip->end_xy.x(), 53.0 + 9.99);
}

TEST(ReportProfileTest, StripStaysInsideTheGrid) {
  TopGrid g = Ground();
  Box(&g, 0.0, 6.0, 90.0, 100.0, 112.0, 2);  // a building in the north-west corner
  const auto strip = PickProfileStrip(g, StripPickOptions{});
  ASSERT_TRUE(strip.has_value());
  for (const Eigen::Vector2d& p : {strip->start_xy, strip->end_xy}) {
    EXPECT_GE(p.x(), 0.0);
    EXPECT_LE(p.x(), 100.0);
    EXPECT_GE(p.y(), 0.0);
    EXPECT_LE(p.y(), 100.0);
  }
}

TEST(ReportProfileTest, PrefersABuildingSurroundedByDataToAHigherOneAtTheBorder) {
  TopGrid g = Ground();
  Box(&g, 0.0, 8.0, 92.0, 100.0, 130.0, 2);   // 30 m high, in the north-west corner (no data beyond the grid)
  Box(&g, 40.0, 55.0, 40.0, 50.0, 112.0, 3);  // 12 m high, inside
  // A third, higher building at the corner of a region without data (east and south of it): not surrounded.
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      const double x = g.CellCenterX(c), y = g.CellCenterY(r);
      if ((x > 60.0 && y < 35.0) || (y < 10.0 && x > 35.0)) g.top_z[g.Index(r, c)] = NAN;
    }
  }
  Box(&g, 50.0, 60.0, 10.0, 20.0, 125.0, 4);
  const auto strip = PickProfileStrip(g, StripPickOptions{});
  ASSERT_TRUE(strip.has_value());
  EXPECT_NEAR(strip->relief_m, 12.0, 1e-4);
  EXPECT_GE(strip->peak_xy.x(), 40.0);
  EXPECT_LE(strip->peak_xy.x(), 55.0);
}

TEST(ReportProfileTest, CandidatesCanBeRestrictedToABox) {
  TopGrid g = Ground();
  Box(&g, 20.0, 30.0, 40.0, 50.0, 130.0, 2);  // 30 m high
  Box(&g, 60.0, 70.0, 40.0, 50.0, 110.0, 3);  // 10 m high, the only one in the box
  StripPickOptions o;
  o.within.Extend(Eigen::Vector2d(50.0, 0.0));
  o.within.Extend(Eigen::Vector2d(100.0, 100.0));
  const auto strip = PickProfileStrip(g, o);
  ASSERT_TRUE(strip.has_value());
  EXPECT_NEAR(strip->relief_m, 10.0, 1e-4);
  // A box without data is ignored.
  o.within = Box2d{};
  o.within.Extend(Eigen::Vector2d(500.0, 500.0));
  o.within.Extend(Eigen::Vector2d(600.0, 600.0));
  EXPECT_NEAR(PickProfileStrip(g, o)->relief_m, 30.0, 1e-4);
}

TEST(ReportProfileTest, EmptyGridHasNoStrip) {
  EXPECT_FALSE(PickProfileStrip(TopGrid(0, 10, 1, 10, 10), StripPickOptions{}).has_value());
}

TEST(ReportProfileTest, AlongMeasuresFromTheStartWithinTheHalfWidth) {
  ProfileStrip s;
  s.start_xy = {10.0, 5.0};
  s.end_xy = {10.0, 25.0};  // northwards
  s.half_width_m = 0.2;
  ASSERT_TRUE(s.Along(10.1, 12.0).has_value());
  EXPECT_NEAR(*s.Along(10.1, 12.0), 7.0, 1e-12);
  EXPECT_FALSE(s.Along(10.3, 12.0).has_value());  // too far across
  EXPECT_FALSE(s.Along(10.0, 4.9).has_value());   // before the start
  EXPECT_FALSE(s.Along(10.0, 25.1).has_value());  // past the end
  const Box2d b = s.Box();
  EXPECT_NEAR(b.min.x(), 9.8, 1e-12);
  EXPECT_NEAR(b.max.x(), 10.2, 1e-12);
  EXPECT_NEAR(b.min.y(), 5.0, 1e-12);
  EXPECT_NEAR(b.max.y(), 25.0, 1e-12);
}

TEST(ReportProfileTest, SampleIsBoundedUniformAndRepeatable) {
  ProfileSample a(1000, 7), b(1000, 7);
  for (int i = 0; i < 100000; ++i) {
    a.Add({static_cast<float>(i), 0.0f, 1});
    b.Add({static_cast<float>(i), 0.0f, 1});
  }
  EXPECT_EQ(a.seen(), 100000u);
  ASSERT_EQ(a.points().size(), 1000u);
  double mean = 0;
  for (size_t i = 0; i < a.points().size(); ++i) {
    mean += a.points()[i].along_m;
    EXPECT_EQ(a.points()[i].along_m, b.points()[i].along_m);
  }
  mean /= 1000.0;
  EXPECT_NEAR(mean, 50000.0, 3000.0);  // uniform over the stream (sd of the mean ~ 900)
  ProfileSample small(10);
  for (int i = 0; i < 5; ++i) small.Add({static_cast<float>(i), 0.0f, 0});
  EXPECT_EQ(small.points().size(), 5u);
}

}  // namespace
}  // namespace sacfuse
