#include "eval/eval.h"

#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "eval/eval_test_scene.h"

namespace sacfuse {
namespace {

using eval_test::BoxScene;
using eval_test::SampleGrid;
using eval_test::SampleRandom;
using eval_test::Shifted;
using Points = std::vector<Eigen::Vector3d>;

EvalOptions Taus(std::vector<double> taus) {
  EvalOptions o;
  o.tau_m = std::move(taus);
  return o;
}

EvalReport Eval(const Points& result, const Points& reference, const EvalOptions& o, const GeoMask* mask = nullptr) {
  return EvaluateClouds(result, {}, reference, mask, o);
}

// Points floating 3-10 m above open ground, at least 3 m from the building.
Points FloatingOutliers(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(0.0, 39.6), z(3.0, 10.0);
  Points out;
  while (out.size() < n) {
    const double x = xy(rng), y = xy(rng);
    if (x > 12.0 && x < 28.0 && y > 12.0 && y < 28.0) continue;
    out.emplace_back(x, y, z(rng));
  }
  return out;
}

// Facade points on the four walls of the box, 0.6-9.4 m high: cameras see them, airborne LiDAR does not.
Points FacadePoints(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> along(15.0, 24.9), z(0.6, 9.4);
  Points out;
  for (size_t i = 0; i < n; ++i) {
    const double a = along(rng), h = z(rng);
    switch (i % 4) {
      case 0: out.emplace_back(14.95, a, h); break;
      case 1: out.emplace_back(24.95, a, h); break;
      case 2: out.emplace_back(a, 14.95, h); break;
      default: out.emplace_back(a, 24.95, h); break;
    }
  }
  return out;
}

Points Concat(Points a, const Points& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(EvaluateCloudsTest, IdenticalCloudsScorePerfect) {
  const Points ref = SampleGrid(BoxScene());
  const EvalReport r = Eval(ref, ref, Taus({0.2, 0.5}));
  ASSERT_EQ(r.scores.size(), 2u);
  for (const auto& s : r.scores) {
    EXPECT_DOUBLE_EQ(s.accuracy, 1.0);
    EXPECT_DOUBLE_EQ(s.completeness, 1.0);
    EXPECT_DOUBLE_EQ(s.f1, 1.0);
    EXPECT_DOUBLE_EQ(s.raw_f1, 1.0);
  }
  EXPECT_EQ(r.result_points, ref.size());
  EXPECT_EQ(r.result_points_evaluated, ref.size());
  EXPECT_EQ(r.result_points_unobserved, 0u);
  EXPECT_DOUBLE_EQ(r.mean_abs_distance_m, 0.0);
  EXPECT_FALSE(r.aligned);
  // Ground right beside the walls stays in the completeness set; only cells straddling a wall may drop out.
  EXPECT_GT(r.reference_points_evaluated, ref.size() - 4 * 36 * 2);
}

TEST(EvaluateCloudsTest, VerticalShiftAgainstThresholds) {
  const Points ref = SampleGrid(BoxScene());
  {  // 0.15 m up, tau 0.2: everything within tau
    const auto s = Eval(Shifted(ref, {0, 0, 0.15}), ref, Taus({0.2})).scores[0];
    EXPECT_DOUBLE_EQ(s.accuracy, 1.0);
    EXPECT_DOUBLE_EQ(s.completeness, 1.0);
  }
  const EvalReport up = Eval(Shifted(ref, {0, 0, 0.3}), ref, Taus({0.2, 0.5}));
  EXPECT_DOUBLE_EQ(up.scores[0].accuracy, 0.0);
  EXPECT_DOUBLE_EQ(up.scores[0].completeness, 0.0);
  EXPECT_DOUBLE_EQ(up.scores[0].f1, 0.0);
  EXPECT_GT(up.scores[0].result_observed, ref.size() * 9 / 10);  // not hidden: it floats in observed space
  EXPECT_DOUBLE_EQ(up.scores[1].accuracy, 1.0);
  EXPECT_DOUBLE_EQ(up.scores[1].completeness, 1.0);
  EXPECT_NEAR(up.mean_abs_distance_m, 0.3, 1e-5);
  EXPECT_NEAR(up.median_abs_distance_m, 0.3, 1e-5);
  // Sunk 0.3 m below the LiDAR surface is an error too, not "unobserved".
  const EvalReport down = Eval(Shifted(ref, {0, 0, -0.3}), ref, Taus({0.2}));
  EXPECT_DOUBLE_EQ(down.scores[0].accuracy, 0.0);
  EXPECT_GT(down.scores[0].result_observed, ref.size() * 9 / 10);
}

TEST(EvaluateCloudsTest, LateralShiftOnlyShowsAtRoofEdges) {
  const Points ref = SampleGrid(BoxScene());
  Points moved;  // 0.4 m east, cropped to the reference extent
  for (const auto& p : Shifted(ref, {0.4, 0, 0})) {
    if (p.x() <= 39.6 + 1e-9) moved.push_back(p);
  }
  const EvalReport r = Eval(moved, ref, Taus({0.2, 0.5}));
  // tau 0.2: on the planes the nearest reference is 0.1 m away; only the 34 roof points pushed 0.4 m past the
  // east eave float in free space. The ground pushed under the west eave is hidden (unobserved).
  const auto& s = r.scores[0];
  EXPECT_EQ(s.result_observed - s.result_accurate, 34u);
  EXPECT_GT(s.result_observed - s.result_accurate, 0u);
  // Incomplete: the west roof column (34) and the x = 0 ground column (133), perhaps the strip east of the box.
  const uint64_t incomplete = s.reference_visible - s.reference_complete;
  EXPECT_GE(incomplete, 34u + 133u);
  EXPECT_LE(incomplete, 34u + 133u + 34u);
  EXPECT_LT(s.completeness, 1.0);
  EXPECT_DOUBLE_EQ(r.scores[1].accuracy, 1.0);
  EXPECT_DOUBLE_EQ(r.scores[1].completeness, 1.0);
}

TEST(EvaluateCloudsTest, DensityOutliersFacadesAndDuplicates) {
  const auto scene = BoxScene();
  const Points ref = SampleGrid(scene);                  // ~11 points / m2
  const Points dense = SampleRandom(scene, 110.0, 0.02, 7);  // 10x denser, mild noise
  Points thinned;
  std::mt19937 rng(3);
  std::bernoulli_distribution keep(0.7);
  for (const auto& p : dense) {
    if (keep(rng)) thinned.push_back(p);
  }
  const EvalOptions o = Taus({0.2, 0.5});
  const EvalReport rd = Eval(dense, ref, o), rt = Eval(thinned, ref, o);
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_NEAR(rd.scores[t].accuracy, rt.scores[t].accuracy, 0.02) << "tau " << o.tau_m[t];
    EXPECT_NEAR(rd.scores[t].f1, rt.scores[t].f1, 0.02) << "tau " << o.tau_m[t];
    EXPECT_GT(rd.scores[t].accuracy, 0.9);
    EXPECT_GT(rd.scores[t].completeness, 0.98);
  }
  // 10 % outliers floating above open ground: clearly worse.
  const Points outliers = FloatingOutliers(dense.size() / 10, 11);
  const EvalReport ro = Eval(Concat(dense, outliers), ref, o);
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_LT(ro.scores[t].accuracy, rd.scores[t].accuracy - 0.05);
    EXPECT_LT(ro.scores[t].f1, rd.scores[t].f1 - 0.02);
    EXPECT_NEAR(ro.scores[t].completeness, rd.scores[t].completeness, 1e-12);
  }
  // Facade points below the eaves are unobserved, not inaccurate: scores unchanged to the last bit.
  const Points facade = FacadePoints(4000, 13);
  const EvalReport rf = Eval(Concat(dense, facade), ref, o);
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_EQ(rf.scores[t].result_observed, rd.scores[t].result_observed);
    EXPECT_DOUBLE_EQ(rf.scores[t].accuracy, rd.scores[t].accuracy);
    EXPECT_DOUBLE_EQ(rf.scores[t].f1, rd.scores[t].f1);
  }
  EXPECT_EQ(rf.result_points_unobserved, rd.result_points_unobserved + facade.size());
  // Duplicating every point (a naive union) gains nothing.
  const EvalReport rdup = Eval(Concat(dense, dense), ref, o);
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_LE(rdup.scores[t].f1, rd.scores[t].f1 + 1e-12);
    EXPECT_LE(rdup.scores[t].raw_f1, rd.scores[t].raw_f1 + 1e-12);
  }
}

TEST(EvaluateCloudsTest, DensityNormalisationOutweighsOversampledRegions) {
  // Half the area perfect at 20 points/m2, the other half 1 m off but sampled 10x more densely: the raw
  // fraction is dominated by the dense bad half, the voxel-normalised accuracy gives each half its area's share.
  const auto scene = eval_test::Scene{};
  const Points ref = SampleGrid(scene);
  Points result;
  for (const auto& p : SampleRandom(scene, 20.0, 0.0, 5)) {
    if (p.x() < 20.0) result.push_back(p);
  }
  for (const auto& p : SampleRandom(scene, 200.0, 0.0, 6)) {
    if (p.x() >= 20.0) result.emplace_back(p.x(), p.y(), 1.0);
  }
  const auto s = Eval(result, ref, Taus({0.5})).scores[0];
  EXPECT_NEAR(s.raw_accuracy, 1.0 / 11.0, 0.02);
  EXPECT_GT(s.accuracy, 0.15);  // the good half holds ~17 % of the occupied voxels
  EXPECT_GT(s.accuracy, 1.7 * s.raw_accuracy);
}

TEST(EvaluateCloudsTest, HalfMissingIsHalfComplete) {
  const Points ref = SampleGrid(BoxScene());
  Points half;
  for (const auto& p : ref) {
    if (p.x() < 20.0) half.push_back(p);
  }
  const auto s = Eval(half, ref, Taus({0.2})).scores[0];
  EXPECT_DOUBLE_EQ(s.accuracy, 1.0);
  EXPECT_NEAR(s.completeness, 0.5, 0.03);
  EXPECT_NEAR(s.raw_completeness, 0.5, 0.03);
  EXPECT_NEAR(s.f1, 2 * 0.5 / 1.5, 0.03);
}

TEST(EvaluateCloudsTest, CompletenessCountsStreetsBesideWallsButNotGroundUnderCanopy) {
  Points ref = SampleGrid(BoxScene());
  for (double x = 5.15; x < 8.0; x += 0.3) {  // a tree: canopy returns at 6 m over x, y in [5, 8]
    for (double y = 5.15; y < 8.0; y += 0.3) ref.emplace_back(x, y, 6.0);
  }
  auto under_canopy = [](const Eigen::Vector3d& p) {
    return p.z() == 0.0 && p.x() > 5.5 && p.x() < 7.5 && p.y() > 5.5 && p.y() < 7.5;
  };
  auto beside_wall = [](const Eigen::Vector3d& p) {  // the ground column 0.25 m west of the box
    return p.z() == 0.0 && std::abs(p.x() - 14.7) < 0.01 && p.y() > 14.9 && p.y() < 25.0;
  };
  Points no_understorey, no_street;
  size_t understorey = 0, street = 0;
  for (const auto& p : ref) {
    if (under_canopy(p)) ++understorey; else no_understorey.push_back(p);
    if (beside_wall(p)) ++street; else no_street.push_back(p);
  }
  ASSERT_EQ(street, 34u);
  ASSERT_GT(understorey, 30u);
  // Cameras cannot see the ground under the canopy: missing it costs nothing.
  const auto a = Eval(no_understorey, ref, Taus({0.2})).scores[0];
  EXPECT_DOUBLE_EQ(a.completeness, 1.0);
  EXPECT_LE(a.reference_visible, ref.size() - understorey);
  // The street beside the wall is visible: missing it is incomplete.
  const auto b = Eval(no_street, ref, Taus({0.2})).scores[0];
  EXPECT_EQ(b.reference_visible - b.reference_complete, street);
  EXPECT_LT(b.completeness, 1.0);
}

TEST(EvaluateCloudsTest, MaskIgnoresEverythingOutside) {
  const Points ref = SampleGrid(BoxScene());
  Points result;
  for (const auto& p : ref) {
    if (p.x() < 20.0) result.push_back(p);
  }
  const Points junk = Shifted(FloatingOutliers(2000, 17), {0, 0, 0});
  size_t junk_east = 0;
  for (const auto& p : junk) {
    if (p.x() >= 20.5) {
      result.push_back(p);
      ++junk_east;
    }
  }
  GeoMask mask;  // x in [0, 20), y in (-1, 40]
  mask.origin_x = 0.0;
  mask.origin_y = 40.0;
  mask.cell_size_m = 0.5;
  mask.width = 40;
  mask.height = 82;
  mask.cells.assign(40 * 82, 255);
  const EvalReport masked = Eval(result, ref, Taus({0.2}), &mask);
  EXPECT_DOUBLE_EQ(masked.scores[0].accuracy, 1.0);
  EXPECT_DOUBLE_EQ(masked.scores[0].completeness, 1.0);
  EXPECT_EQ(masked.result_points_outside_mask, junk_east);
  EXPECT_DOUBLE_EQ(masked.area_m2, 40 * 82 * 0.25);
  EXPECT_DOUBLE_EQ(masked.points_per_m2, (result.size() - junk_east) / masked.area_m2);
  EXPECT_LT(masked.reference_points_evaluated, ref.size() * 0.55);
  const EvalReport open = Eval(result, ref, Taus({0.2}));
  EXPECT_LT(open.scores[0].accuracy, 0.95);
  EXPECT_LT(open.scores[0].completeness, 0.6);
  EXPECT_EQ(open.result_points_outside_mask, 0u);
}

TEST(EvaluateCloudsTest, UtmCoordinatesScoreLikeLocalOnes) {
  const auto scene = BoxScene();
  const Points ref = SampleGrid(scene);
  const Points result = Concat(SampleRandom(scene, 30.0, 0.05, 21), FloatingOutliers(3000, 22));
  const Eigen::Vector3d utm(390000.0, 5705000.0, 100.0);
  EvalOptions o = Taus({0.1, 0.2, 0.5});
  const EvalReport local = Eval(result, ref, o);
  const EvalReport far = Eval(Shifted(result, utm), Shifted(ref, utm), o);
  ASSERT_EQ(local.scores.size(), far.scores.size());
  for (size_t t = 0; t < local.scores.size(); ++t) {
    EXPECT_NEAR(far.scores[t].accuracy, local.scores[t].accuracy, 1e-9);
    EXPECT_NEAR(far.scores[t].completeness, local.scores[t].completeness, 1e-9);
    EXPECT_NEAR(far.scores[t].raw_f1, local.scores[t].raw_f1, 1e-9);
    EXPECT_LT(local.scores[t].accuracy, 0.99);  // the outliers are visible at every threshold
  }
  EXPECT_NEAR(far.mean_abs_distance_m, local.mean_abs_distance_m, 1e-6);
  EXPECT_NEAR(far.median_abs_distance_m, local.median_abs_distance_m, 1e-6);
  EXPECT_NEAR(far.area_m2, local.area_m2, 1e-6);
}

TEST(EvaluateCloudsTest, SourceIdHistogramAndArgumentErrors) {
  const Points ref = SampleGrid(BoxScene());
  std::vector<uint16_t> ids(ref.size());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<uint16_t>(1 + i % 3);
  const EvalReport r = EvaluateClouds(ref, ids, ref, nullptr, EvalOptions{});
  ASSERT_EQ(r.source_id_histogram.size(), 3u);
  EXPECT_EQ(r.source_id_histogram.at(1) + r.source_id_histogram.at(2) + r.source_id_histogram.at(3), ref.size());
  EXPECT_EQ(r.source_id_histogram.at(1), (ref.size() + 2) / 3);
  ASSERT_EQ(r.scores.size(), 2u);  // default 2 x and 5 x GSD
  EXPECT_DOUBLE_EQ(r.scores[0].tau_m, 0.2);
  EXPECT_DOUBLE_EQ(r.scores[1].tau_m, 0.5);
  EXPECT_NEAR(r.points_per_m2, ref.size() / r.area_m2, 1e-9);

  EXPECT_THROW(EvaluateClouds(ref, {1, 2}, ref, nullptr, EvalOptions{}), Error);
  EXPECT_THROW(EvaluateClouds(ref, {}, {}, nullptr, EvalOptions{}), Error);
  Points bad = ref;
  bad[5].x() = std::nan("");
  EXPECT_THROW(EvaluateClouds(bad, {}, ref, nullptr, EvalOptions{}), Error);
  EvalOptions wrong;
  wrong.gsd_m = -1;
  EXPECT_THROW(EvaluateClouds(ref, {}, ref, nullptr, wrong), ConfigError);
  // An empty result is valid and scores zero.
  const EvalReport empty = EvaluateClouds({}, {}, ref, nullptr, EvalOptions{});
  EXPECT_DOUBLE_EQ(empty.scores[0].f1, 0.0);
  EXPECT_EQ(empty.result_points, 0u);
}

}  // namespace
}  // namespace sacfuse
