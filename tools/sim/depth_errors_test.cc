#include "tools/sim/depth_errors.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/backproject.h"
#include "tools/sim/depth_normals.h"
#include "tools/sim/flight_plan.h"
#include "tools/sim/render.h"
#include "tools/sim/simple_scenes.h"

namespace sacfuse::sim {
namespace {

constexpr double kGround = 100.0;
constexpr double kHeight = 200.0;

Rigid3d NadirPose(double x, double y) {
  const Rigid3d world_from_cam{Eigen::Quaterniond(WorldFromCameraRotation({0, 1}, 0.0)),
                               Eigen::Vector3d(x, y, kGround + kHeight)};
  return world_from_cam.Inverse();
}

DepthMap RenderDepth(const Surface& s, const PinholeCamera& cam, const Rigid3d& pose) {
  RenderRequest r;
  r.surface = &s;
  r.camera = cam;
  r.cam_from_world = pose;
  r.render_image = false;
  return RenderView(r).depth;
}

// Every model off; tests switch one on at a time.
SimErrorOptions AllOff() {
  SimErrorOptions o;
  o.pose_position_sigma_m = 0.0;
  o.pose_rotation_sigma_deg = 0.0;
  o.disparity_sigma_px = 0.0;
  o.bias_amplitude_m = 0.0;
  o.fattening_px = 0;
  o.blunders_per_mpx = 0.0;
  o.occlusion_strip_px = 0;
  o.dropout_fraction = 0.0;
  o.keypoint_sigma_px = 0.0;
  return o;
}

TEST(DepthErrorsTest, DisabledIsExact) {
  const BoxScene plane(kGround);
  const PinholeCamera cam = PinholeCamera::Centered(200, 150, 1000.0);
  const DepthMap truth = RenderDepth(plane, cam, NadirPose(0, 0));
  SimErrorOptions o;
  o.enabled = false;
  const ViewErrorModel m = MakeViewErrorModel(o, false, cam.fx, 50.0, 1, true);
  DepthErrorReport rep;
  const DepthMap d = ApplyDepthErrors(truth, m, 7, &rep);
  EXPECT_TRUE(d.data == truth.data);
  EXPECT_EQ(rep.valid_out, truth.num_pixels());
  const PoseError pe = DrawPoseError(o, 7);
  EXPECT_EQ(pe.center_delta_m, Eigen::Vector3d::Zero());
}

TEST(DepthErrorsTest, PoseErrorOffsetsTheCloudRigidly) {
  const BoxScene scene(kGround, Box2d{-20, -15, 20, 15}, 12.0);
  const PinholeCamera cam = PinholeCamera::Centered(240, 180, 1000.0);
  const Rigid3d truth_pose = NadirPose(3.0, -2.0);
  const DepthMap depth = RenderDepth(scene, cam, truth_pose);
  SimErrorOptions o = AllOff();
  o.pose_position_sigma_m = 0.5;
  // Position only: every back-projected point moves by the centre delta.
  PoseError pe = DrawPoseError(o, 11);
  ASSERT_GT(pe.center_delta_m.norm(), 0.05);
  EXPECT_EQ(pe.rotation_delta_rad, Eigen::Vector3d::Zero());
  Rigid3d written = ApplyPoseError(truth_pose, pe);
  const Rigid3d true_wc = truth_pose.Inverse();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double worst = 0.0;
  for (int row = 0; row < cam.height; ++row) {
    for (int col = 0; col < cam.width; ++col) {
      const double d = depth.at(row, col);
      const Eigen::Vector3d delta = DepthPixelToWorld(cam, written.Inverse(), col, row, d) -
                                    DepthPixelToWorld(cam, true_wc, col, row, d);
      mean += delta;
      worst = std::max(worst, (delta - pe.center_delta_m).norm());
    }
  }
  mean /= static_cast<double>(cam.width * cam.height);
  EXPECT_LT((mean - pe.center_delta_m).norm(), 1e-6);
  EXPECT_LT(worst, 1e-5);
  // With rotation too: the cloud moves by the rigid transform T'_wc T_cw, close to the centre delta plus the
  // rotation lever arm (angle x range).
  o.pose_rotation_sigma_deg = 0.01;
  pe = DrawPoseError(o, 12);
  written = ApplyPoseError(truth_pose, pe);
  const Rigid3d rigid = written.Inverse() * truth_pose;
  const double lever = pe.rotation_delta_rad.norm() * (kHeight + 10.0);
  for (int row = 0; row < cam.height; row += 7) {
    for (int col = 0; col < cam.width; col += 7) {
      const double d = depth.at(row, col);
      const Eigen::Vector3d t = DepthPixelToWorld(cam, true_wc, col, row, d);
      const Eigen::Vector3d w = DepthPixelToWorld(cam, written.Inverse(), col, row, d);
      EXPECT_LT((w - rigid * t).norm(), 1e-5);
      EXPECT_LT((w - t - pe.center_delta_m).norm(), lever + 1e-3);
    }
  }
}

TEST(DepthErrorsTest, StereoNoiseSigmaMatchesFormula) {
  const BoxScene plane(kGround);
  const PinholeCamera cam = PinholeCamera::Centered(600, 450, 1500.0);
  const DepthMap truth = RenderDepth(plane, cam, NadirPose(0, 0));
  SimErrorOptions o = AllOff();
  o.disparity_sigma_px = 0.5;
  o.noise_correlation_px = 3.0;
  const double baseline = 40.0;
  const ViewErrorModel m = MakeViewErrorModel(o, false, cam.fx, baseline, 1, true);
  const DepthMap noisy = ApplyDepthErrors(truth, m, 99, nullptr);
  double sum = 0.0, sum2 = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < truth.data.size(); ++i) {
    const double e = noisy.data[i] - truth.data[i];
    sum += e;
    sum2 += e * e;
    ++n;
  }
  const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  const double expected = kHeight * kHeight * 0.5 / (1500.0 * baseline);  // z^2 sigma_d / (f B) = 0.333 m
  EXPECT_NEAR(sigma / expected, 1.0, 0.15);
  // Obliques are noisier by oblique_factor.
  const ViewErrorModel mo = MakeViewErrorModel(o, true, cam.fx, baseline, 1, true);
  EXPECT_DOUBLE_EQ(mo.StereoSigma(kHeight), o.oblique_factor * m.StereoSigma(kHeight));
  // `scale` multiplies the magnitude.
  o.scale = 2.0;
  EXPECT_DOUBLE_EQ(MakeViewErrorModel(o, false, cam.fx, baseline, 1, true).StereoSigma(kHeight),
                   2.0 * m.StereoSigma(kHeight));
}

TEST(DepthErrorsTest, BlunderAndDropoutFractions) {
  const BoxScene plane(kGround);
  const PinholeCamera cam = PinholeCamera::Centered(800, 600, 1500.0);
  const DepthMap truth = RenderDepth(plane, cam, NadirPose(0, 0));
  SimErrorOptions o = AllOff();
  o.blunders_per_mpx = 400.0;
  o.blunder_radius_px = 6.0;
  o.blunder_depth_sigma_m = 3.0;
  o.dropout_fraction = 0.05;
  const ViewErrorModel m = MakeViewErrorModel(o, false, cam.fx, 50.0, 1, true);
  DepthErrorReport rep;
  const DepthMap d = ApplyDepthErrors(truth, m, 5, &rep);
  size_t invalid = 0, moved = 0;
  for (size_t i = 0; i < d.data.size(); ++i) {
    if (d.data[i] <= 0.0f) {
      ++invalid;
    } else if (std::abs(d.data[i] - truth.data[i]) > 1.0) {
      ++moved;
    }
  }
  const double npx = static_cast<double>(d.data.size());
  EXPECT_NEAR(invalid / npx, 0.05, 0.0125);  // dropouts within 25 %
  EXPECT_EQ(invalid, rep.dropout_pixels);
  // Blobs cover 1 - exp(-rate pi E[r^2]) of the pixels (E[r^2] = 13/12 r^2), minus the dropped ones.
  const double expected = 1.0 - std::exp(-400e-6 * M_PI * 13.0 / 12.0 * 36.0);
  EXPECT_NEAR(rep.blunder_pixels / npx, expected, 0.25 * expected);
  EXPECT_NEAR(static_cast<double>(moved) / npx, expected * 0.95, 0.25 * expected);
  EXPECT_NEAR(rep.blunder_count, 400e-6 * npx, 5.0 * std::sqrt(400e-6 * npx));
}

TEST(DepthErrorsTest, FatteningAndOcclusionAtEdgesOnly) {
  const BoxScene scene(kGround, Box2d{-15, -10, 15, 10}, 10.0);
  const PinholeCamera cam = PinholeCamera::Centered(300, 220, 1000.0);
  const DepthMap truth = RenderDepth(scene, cam, NadirPose(0, 0));
  SimErrorOptions o = AllOff();
  o.fattening_px = 2;
  o.occlusion_strip_px = 3;
  const ViewErrorModel m = MakeViewErrorModel(o, false, cam.fx, 50.0, 1, /*baseline_along_columns=*/true);
  DepthErrorReport rep;
  const DepthMap d = ApplyDepthErrors(truth, m, 5, &rep);
  EXPECT_GT(rep.fattened_pixels, 0u);
  EXPECT_GT(rep.occluded_pixels, 0u);
  const float roof = static_cast<float>(kHeight - 10.0);
  for (int row = 0; row < d.height; ++row) {
    for (int col = 0; col < d.width; ++col) {
      const float t = truth.at(row, col), v = d.at(row, col);
      if (v == t) continue;
      // Only ground pixels change: into roof depth (fattened) or invalid (occlusion strip), near the box.
      EXPECT_NEAR(t, kHeight, 1e-3);
      EXPECT_TRUE(v == 0.0f || std::abs(v - roof) < 1e-3) << v;
      int near_roof = 0;
      for (int dr = -5; dr <= 5; ++dr) {
        for (int dc = -5; dc <= 5; ++dc) {
          near_roof += truth.Contains(row + dr, col + dc) && std::abs(truth.at(row + dr, col + dc) - roof) < 1e-3;
        }
      }
      EXPECT_GT(near_roof, 0);
    }
  }
  // Occlusion strips run along the baseline axis (image columns here): left and right of the box only.
  const int mid_row = d.height / 2;
  int invalid_in_mid_row = 0;
  for (int col = 0; col < d.width; ++col) invalid_in_mid_row += d.at(mid_row, col) == 0.0f;
  EXPECT_EQ(invalid_in_mid_row, 2 * 3);
}

TEST(DepthErrorsTest, SameKeySameOutput) {
  const BoxScene plane(kGround);
  const PinholeCamera cam = PinholeCamera::Centered(160, 120, 800.0);
  const DepthMap truth = RenderDepth(plane, cam, NadirPose(0, 0));
  const ViewErrorModel m = MakeViewErrorModel(SimErrorOptions(), false, cam.fx, 50.0, 1, true);
  EXPECT_TRUE(ApplyDepthErrors(truth, m, 1, nullptr).data == ApplyDepthErrors(truth, m, 1, nullptr).data);
  EXPECT_FALSE(ApplyDepthErrors(truth, m, 1, nullptr).data == ApplyDepthErrors(truth, m, 2, nullptr).data);
}

TEST(DepthNormalsTest, PlaneNormalsFaceTheCamera) {
  const BoxScene plane(kGround);
  const PinholeCamera cam = PinholeCamera::Centered(120, 90, 600.0);
  const Rigid3d pose = NadirPose(0, 0);
  const DepthMap depth = RenderDepth(plane, cam, pose);
  const NormalMap n = NormalsFromDepth(depth, cam);
  // World up in the camera frame.
  const Eigen::Vector3d up = pose.rotation * Eigen::Vector3d::UnitZ();
  for (int row = 0; row < n.height; ++row) {
    for (int col = 0; col < n.width; ++col) {
      const Eigen::Vector3d v(n.at(row, col, 0), n.at(row, col, 1), n.at(row, col, 2));
      EXPECT_NEAR(v.dot(up), 1.0, 1e-4);
    }
  }
}

}  // namespace
}  // namespace sacfuse::sim
