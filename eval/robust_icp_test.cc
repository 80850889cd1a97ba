#include "eval/robust_icp.h"

#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "eval/eval.h"
#include "eval/eval_test_scene.h"

namespace sacfuse {
namespace {

using Points = std::vector<Eigen::Vector3d>;
constexpr double kPi = 3.14159265358979323846;

// 0.5 degree about z around the block centre, then (0.4, -0.3, 0.2) m: reference -> misaligned result.
Eigen::Matrix4d Perturbation(const Eigen::Vector3d& centre) {
  Eigen::Affine3d t = Eigen::Translation3d(Eigen::Vector3d(0.4, -0.3, 0.2) + centre) *
                      Eigen::AngleAxisd(0.5 * kPi / 180.0, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(-centre);
  return t.matrix();
}

Points Apply(const Eigen::Matrix4d& m, Points points) {
  for (auto& p : points) p = m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
  return points;
}

// Noisy photogrammetric-like result with 5 % gross outliers anywhere in the block.
Points NoisyResult(const eval_test::Scene& scene, const Eigen::Vector3d& offset) {
  Points result = eval_test::SampleRandom(scene, 25.0, 0.03, 31);
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> xy(0.0, 40.0), z(-2.0, 15.0);
  const size_t outliers = result.size() / 19;  // 5 % of the total
  for (size_t i = 0; i < outliers; ++i) result.emplace_back(xy(rng), xy(rng), z(rng));
  return eval_test::Shifted(result, offset);
}

struct Residual {
  double angle_deg, max_shift_m;
};

// How far `alignment` is from undoing `perturbation`, measured over the block's corners and centre.
Residual Compare(const Eigen::Matrix4d& alignment, const Eigen::Matrix4d& perturbation, const Eigen::Vector3d& offset) {
  const Eigen::Matrix4d e = alignment * perturbation;
  Residual r{Eigen::AngleAxisd(Eigen::Matrix3d(e.topLeftCorner<3, 3>())).angle() * 180.0 / kPi, 0.0};
  for (double x : {0.0, 20.0, 40.0}) {
    for (double y : {0.0, 20.0, 40.0}) {
      const Eigen::Vector3d p = offset + Eigen::Vector3d(x, y, 5.0);
      r.max_shift_m = std::max(r.max_shift_m, (e.topLeftCorner<3, 3>() * p + e.topRightCorner<3, 1>() - p).norm());
    }
  }
  return r;
}

class RobustIcpTest : public ::testing::TestWithParam<Eigen::Vector3d> {};

TEST_P(RobustIcpTest, RecoversRotationAndShiftAndTheScore) {
  const Eigen::Vector3d offset = GetParam();  // the block near the origin and at UTM coordinates
  const auto scene = eval_test::GableScene();
  const Points ref = eval_test::Shifted(eval_test::SampleGrid(scene), offset);
  const Points truth = NoisyResult(scene, offset);
  const Eigen::Matrix4d perturbation = Perturbation(offset + Eigen::Vector3d(20, 20, 0));
  const Points moved = Apply(perturbation, truth);

  EvalOptions o;  // tau 0.2 and 0.5 m
  const EvalReport baseline = EvaluateClouds(truth, {}, ref, nullptr, o);
  const EvalReport unaligned = EvaluateClouds(moved, {}, ref, nullptr, o);
  o.align = true;
  const EvalReport aligned = EvaluateClouds(moved, {}, ref, nullptr, o);
  ASSERT_TRUE(aligned.aligned);

  const Residual res = Compare(aligned.alignment, perturbation, offset);
  EXPECT_LT(res.angle_deg, 0.02);
  EXPECT_LT(res.max_shift_m, 0.02);
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_GE(aligned.scores[t].f1, 0.95 * baseline.scores[t].f1) << "tau " << aligned.scores[t].tau_m;
  }
  EXPECT_LT(unaligned.scores[0].f1, 0.9 * baseline.scores[0].f1) << "the perturbation must hurt at tau 0.2 m";
}

INSTANTIATE_TEST_SUITE_P(Frames, RobustIcpTest,
                         ::testing::Values(Eigen::Vector3d::Zero(), Eigen::Vector3d(390000.0, 5705000.0, 100.0)));

TEST(RobustIcpModesTest, PointToPointAlsoConvergesAndRunsAreDeterministic) {
  const auto scene = eval_test::GableScene();
  const Points ref = eval_test::SampleGrid(scene);
  const Eigen::Matrix4d perturbation = Perturbation(Eigen::Vector3d(20, 20, 0));
  const Points moved = Apply(perturbation, NoisyResult(scene, Eigen::Vector3d::Zero()));
  EvalOptions o;
  o.align = true;
  o.align_max_points = 20000;  // exercises the seeded subsample
  const EvalReport a = EvaluateClouds(moved, {}, ref, nullptr, o);
  const EvalReport b = EvaluateClouds(moved, {}, ref, nullptr, o);
  EXPECT_EQ(a.alignment, b.alignment);
  EXPECT_LT(Compare(a.alignment, perturbation, Eigen::Vector3d::Zero()).max_shift_m, 0.03);
  // Point to point slides only slowly along nadir-sampled planes (hence point_to_plane is the default), but it
  // fixes the height at once and heads the right way.
  o.align_mode = "point_to_point";
  o.align_max_iterations = 100;
  const EvalReport p = EvaluateClouds(moved, {}, ref, nullptr, o);
  const Residual rp = Compare(p.alignment, perturbation, Eigen::Vector3d::Zero());
  const Residual none = Compare(Eigen::Matrix4d::Identity(), perturbation, Eigen::Vector3d::Zero());
  EXPECT_LT(rp.max_shift_m, 0.5 * none.max_shift_m);
  EXPECT_LT(rp.angle_deg, 0.25);
  EXPECT_NEAR((p.alignment * perturbation)(2, 3), 0.0, 0.01);
}

TEST(RobustIcpModesTest, FlatSceneDoesNotSlide) {
  // A flat plane constrains only z and the tilts: the damped solver must leave x, y and yaw alone.
  const eval_test::Scene flat;
  const Points ref = eval_test::SampleGrid(flat);
  const Points moved = eval_test::Shifted(eval_test::SampleRandom(flat, 20.0, 0.02, 41), {0, 0, 0.25});
  EvalOptions o;
  o.align = true;
  const EvalReport r = EvaluateClouds(moved, {}, ref, nullptr, o);
  EXPECT_NEAR(r.alignment(2, 3), -0.25, 0.01);
  EXPECT_LT(std::abs(r.alignment(0, 3)) + std::abs(r.alignment(1, 3)), 0.05);
  EXPECT_GT(r.scores[0].f1, 0.9);
}

}  // namespace
}  // namespace sacfuse
