#include "tools/sim/flight_plan.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "tools/sim/sim_options.h"

namespace sacfuse::sim {
namespace {

Box2d AreaOf(const SimOptions& o) {
  return {o.origin_east_m, o.origin_north_m, o.origin_east_m + o.area_width_m, o.origin_north_m + o.area_height_m};
}

bool InQuad(const std::vector<Eigen::Vector2d>& q, const Eigen::Vector2d& p) {
  int sign = 0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d e = q[(k + 1) % 4] - q[k], d = p - q[k];
    const int s = e.x() * d.y() - e.y() * d.x() >= 0.0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

TEST(FlightPlanTest, DortmundMatchesTableII) {
  const SimOptions o = SimPreset("dortmund");
  const FlightPlan plan = PlanFlight(o, AreaOf(o), o.ground_height_m);
  EXPECT_EQ(plan.num_nadir(), 16);
  EXPECT_EQ(plan.num_oblique(), 43);
  EXPECT_NEAR(plan.nadir_focal_px, 50.0 / 0.006, 1e-6);
  EXPECT_NEAR(plan.oblique_focal_px, 80.0 / 0.006, 1e-6);
  EXPECT_NEAR(plan.flying_height_m, 0.10 * 50.0 / 0.006, 1e-6);  // H = gsd x f
  EXPECT_NEAR(plan.baseline_m, 0.25 * 6132 * 0.10, 1e-9);
  EXPECT_NEAR(plan.line_spacing_m, 0.20 * 8176 * 0.10, 1e-9);
  for (const PlannedView& v : plan.views) {
    if (v.kind == ViewKind::kNadir) {
      EXPECT_EQ(v.camera.width, 6132);
      EXPECT_EQ(v.camera.height, 8176);
    } else {
      EXPECT_EQ(v.camera.width, 8176);
      EXPECT_EQ(v.camera.height, 6132);
    }
  }
  // Forward overlap of consecutive nadir footprints on the ground = 75 %, side overlap between lines = 80 %.
  std::vector<const PlannedView*> nadir;
  for (const PlannedView& v : plan.views) {
    if (v.kind == ViewKind::kNadir) nadir.push_back(&v);
  }
  int pairs_along = 0, pairs_across = 0;
  for (const PlannedView* a : nadir) {
    for (const PlannedView* b : nadir) {
      const Eigen::Vector3d d = b->cam_from_world.Inverse().translation - a->cam_from_world.Inverse().translation;
      std::vector<Eigen::Vector2d> fa, fb;
      ASSERT_TRUE(FootprintOnPlane(a->camera, a->cam_from_world, o.ground_height_m, &fa));
      ASSERT_TRUE(FootprintOnPlane(b->camera, b->cam_from_world, o.ground_height_m, &fb));
      const Box2d box_a{fa[0].x(), fa[2].y(), fa[2].x(), fa[0].y()};  // nadir: top-left = north-west
      const double overlap = ClippedArea(fb, box_a) / (box_a.Width() * box_a.Height());
      if (std::abs(d.y()) < 1e-6 && std::abs(d.x() - plan.baseline_m) < 1e-6) {
        EXPECT_NEAR(overlap, 0.75, 1e-6);
        ++pairs_along;
      }
      if (std::abs(d.x()) < 1e-6 && std::abs(d.y() - plan.line_spacing_m) < 1e-6) {
        EXPECT_NEAR(overlap, 0.80, 1e-6);
        ++pairs_across;
      }
    }
  }
  EXPECT_GT(pairs_along, 0);
  EXPECT_GT(pairs_across, 0);
}

TEST(FlightPlanTest, ObliquesLookTheirWay) {
  const SimOptions o = SimPreset("small");
  const FlightPlan plan = PlanFlight(o, AreaOf(o), o.ground_height_m);
  std::set<std::string> names;
  for (const PlannedView& v : plan.views) {
    EXPECT_TRUE(names.insert(v.name).second) << v.name;
    EXPECT_EQ(v.name.rfind(std::string(ViewKindName(v.kind)) + "/", 0), 0u) << v.name;
    const Eigen::Vector3d dir = v.cam_from_world.rotation.conjugate() * Eigen::Vector3d::UnitZ();
    const double tilt = std::acos(-dir.z()) * 180.0 / M_PI;
    if (v.kind == ViewKind::kNadir) {
      EXPECT_NEAR(tilt, 0.0, 1e-9);
    } else {
      EXPECT_NEAR(tilt, o.oblique_tilt_deg, 1e-9);
    }
    if (v.kind == ViewKind::kObliqueForward) {
      EXPECT_GT(dir.x(), 0.5);
    } else if (v.kind == ViewKind::kObliqueBackward) {
      EXPECT_LT(dir.x(), -0.5);
    } else if (v.kind == ViewKind::kObliqueLeft) {
      EXPECT_GT(dir.y(), 0.5);
    } else if (v.kind == ViewKind::kObliqueRight) {
      EXPECT_LT(dir.y(), -0.5);
    }
    // Rotation is proper (right-handed camera frame).
    EXPECT_NEAR(v.cam_from_world.rotation.toRotationMatrix().determinant(), 1.0, 1e-12);
  }
}

// Every preset that tests and the demo use: the documented number of views, and each ground point of the area
// lies in the footprints of several views.
TEST(FlightPlanTest, TinyAndSmallCoverTheArea) {
  struct Expect {
    const char* preset;
    int min_views, max_views, min_coverage;
  };
  for (const Expect& e : {Expect{"tiny", 10, 20, 4}, Expect{"small", 30, 60, 3}}) {
    const SimOptions o = SimPreset(e.preset);
    const Box2d area = AreaOf(o);
    const FlightPlan plan = PlanFlight(o, area, o.ground_height_m);
    EXPECT_GE(static_cast<int>(plan.views.size()), e.min_views) << e.preset;
    EXPECT_LE(static_cast<int>(plan.views.size()), e.max_views) << e.preset;
    EXPECT_GT(plan.num_nadir(), 0);
    EXPECT_GT(plan.num_oblique(), 0);
    std::vector<std::vector<Eigen::Vector2d>> footprints;
    for (const PlannedView& v : plan.views) {
      footprints.emplace_back();
      ASSERT_TRUE(FootprintOnPlane(v.camera, v.cam_from_world, o.ground_height_m, &footprints.back()));
    }
    int min_coverage = 1 << 30;
    for (int j = 0; j < 20; ++j) {
      for (int i = 0; i < 20; ++i) {
        const Eigen::Vector2d p(area.min.x() + (i + 0.5) * area.Width() / 20, area.min.y() + (j + 0.5) * area.Height() / 20);
        int count = 0;
        for (const auto& f : footprints) count += InQuad(f, p) ? 1 : 0;
        min_coverage = std::min(min_coverage, count);
      }
    }
    EXPECT_GE(min_coverage, e.min_coverage) << e.preset;
  }
}

TEST(FlightPlanTest, CapsKeepViewsNearestTheCentre) {
  SimOptions o = SimPreset("small");
  o.max_nadir_views = 0;
  o.max_oblique_views = 0;
  const Box2d area = AreaOf(o);
  const FlightPlan all = PlanFlight(o, area, o.ground_height_m);
  o.max_nadir_views = 3;
  o.max_oblique_views = 5;
  const FlightPlan capped = PlanFlight(o, area, o.ground_height_m);
  EXPECT_EQ(capped.num_nadir(), 3);
  EXPECT_EQ(capped.num_oblique(), 5);
  EXPECT_GT(all.num_nadir(), 3);
  EXPECT_EQ(all.candidate_nadir, all.num_nadir());
  double worst_kept = 0.0, best_dropped = 1e300;
  for (const PlannedView& v : all.views) {
    if (v.kind != ViewKind::kNadir) continue;
    const double d = (v.footprint_center - area.Center()).norm();
    bool kept = false;
    for (const PlannedView& c : capped.views) {
      kept |= c.kind == ViewKind::kNadir && (c.footprint_center - v.footprint_center).norm() < 1e-9;
    }
    if (kept) worst_kept = std::max(worst_kept, d);
    if (!kept) best_dropped = std::min(best_dropped, d);
  }
  EXPECT_LE(worst_kept, best_dropped + 1e-9);
  for (const PlannedView& v : all.views) EXPECT_GT(v.footprint_in_area_m2, 0.0);
}

}  // namespace
}  // namespace sacfuse::sim
