#include "core/photogrammetric_orientation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/camera.h"

namespace sacfuse {
namespace {

constexpr double kTol = 1e-12;

void ExpectVectorNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = kTol) {
  EXPECT_LT((a - b).norm(), tol) << "got " << a.transpose() << ", expected " << b.transpose();
}

// World direction of a sacfuse camera axis.
Eigen::Vector3d AxisInWorld(const Rigid3d& cam_from_world, const Eigen::Vector3d& axis_in_cam) {
  return cam_from_world.rotation.conjugate() * axis_in_cam;
}
const Eigen::Vector3d kRight(1, 0, 0), kImageUp(0, -1, 0), kForward(0, 0, 1);  // in sacfuse's camera frame

TEST(PhotogrammetricOrientationTest, ZeroAnglesAreANadirCameraWithEastRightAndNorthUp) {
  const Eigen::Vector3d centre(500.0, 200.0, 1000.0);
  const Rigid3d pose = CamFromWorldFromPhotogrammetric(ObjectFromPhotoCameraRotation({0, 0, 0}), centre);
  ExpectVectorNear(AxisInWorld(pose, kForward), {0, 0, -1});  // looks down
  ExpectVectorNear(AxisInWorld(pose, kRight), {1, 0, 0});     // image x along east
  ExpectVectorNear(AxisInWorld(pose, kImageUp), {0, 1, 0});   // image top toward north
  ExpectVectorNear(pose.Inverse().translation, centre, 1e-9);
  // A ground point 10 m east and 20 m north of the nadir, 1000 m below: right of and above the principal point.
  const PinholeCamera cam = PinholeCamera::Centered(1000, 800, 2000.0);
  const Eigen::Vector2d uv = cam.Project(pose * Eigen::Vector3d(510.0, 220.0, 0.0));
  EXPECT_NEAR(uv.x(), 500.0 + 2000.0 * 10.0 / 1000.0, 1e-9);
  EXPECT_NEAR(uv.y(), 400.0 - 2000.0 * 20.0 / 1000.0, 1e-9);
}

TEST(PhotogrammetricOrientationTest, NinetyDegreeCases) {
  const Eigen::Vector3d c(0, 0, 0);
  {  // kappa = 90: image x toward north, image top toward west, still looking down.
    const Rigid3d pose = CamFromWorldFromPhotogrammetric(ObjectFromPhotoCameraRotation({0, 0, 90}), c);
    ExpectVectorNear(AxisInWorld(pose, kForward), {0, 0, -1});
    ExpectVectorNear(AxisInWorld(pose, kRight), {0, 1, 0});
    ExpectVectorNear(AxisInWorld(pose, kImageUp), {-1, 0, 0});
  }
  {  // omega = 90: looks horizontally north, image top up, image x east.
    const Rigid3d pose = CamFromWorldFromPhotogrammetric(ObjectFromPhotoCameraRotation({90, 0, 0}), c);
    ExpectVectorNear(AxisInWorld(pose, kForward), {0, 1, 0});
    ExpectVectorNear(AxisInWorld(pose, kImageUp), {0, 0, 1});
    ExpectVectorNear(AxisInWorld(pose, kRight), {1, 0, 0});
  }
  {  // phi = 90: looks horizontally west, image top north, image x down.
    const Rigid3d pose = CamFromWorldFromPhotogrammetric(ObjectFromPhotoCameraRotation({0, 90, 0}), c);
    ExpectVectorNear(AxisInWorld(pose, kForward), {-1, 0, 0});
    ExpectVectorNear(AxisInWorld(pose, kImageUp), {0, 1, 0});
    ExpectVectorNear(AxisInWorld(pose, kRight), {0, 0, -1});
  }
  {  // 45-degree forward oblique (tilted toward north about the x axis): looks north and down.
    const Rigid3d pose = CamFromWorldFromPhotogrammetric(ObjectFromPhotoCameraRotation({45, 0, 0}), c);
    ExpectVectorNear(AxisInWorld(pose, kForward), Eigen::Vector3d(0, 1, -1).normalized());
  }
}

TEST(PhotogrammetricOrientationTest, MatrixElementsAreTheTextbookOnes) {
  const double w = 0.3, p = -0.7, k = 2.1;  // radians
  const Eigen::Matrix3d r = ObjectFromPhotoCameraRotation({w * 180.0 / M_PI, p * 180.0 / M_PI, k * 180.0 / M_PI});
  EXPECT_NEAR(r(0, 0), std::cos(p) * std::cos(k), kTol);
  EXPECT_NEAR(r(0, 1), -std::cos(p) * std::sin(k), kTol);
  EXPECT_NEAR(r(0, 2), std::sin(p), kTol);
  EXPECT_NEAR(r(1, 0), std::cos(w) * std::sin(k) + std::sin(w) * std::sin(p) * std::cos(k), kTol);
  EXPECT_NEAR(r(1, 1), std::cos(w) * std::cos(k) - std::sin(w) * std::sin(p) * std::sin(k), kTol);
  EXPECT_NEAR(r(1, 2), -std::sin(w) * std::cos(p), kTol);
  EXPECT_NEAR(r(2, 0), std::sin(w) * std::sin(k) - std::cos(w) * std::sin(p) * std::cos(k), kTol);
  EXPECT_NEAR(r(2, 1), std::sin(w) * std::cos(k) + std::cos(w) * std::sin(p) * std::sin(k), kTol);
  EXPECT_NEAR(r(2, 2), std::cos(w) * std::cos(p), kTol);
}

TEST(PhotogrammetricOrientationTest, AnglesRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> wk(-179.0, 179.0), ph(-89.0, 89.0);
  for (int i = 0; i < 200; ++i) {
    const OmegaPhiKappa a{wk(rng), ph(rng), wk(rng)};
    const OmegaPhiKappa b = OmegaPhiKappaFromRotation(ObjectFromPhotoCameraRotation(a));
    EXPECT_NEAR(b.omega_deg, a.omega_deg, 1e-9);
    EXPECT_NEAR(b.phi_deg, a.phi_deg, 1e-9);
    EXPECT_NEAR(b.kappa_deg, a.kappa_deg, 1e-9);
  }
  // Gimbal lock: the angles differ but the matrix is the same.
  for (const double phi : {90.0, -90.0}) {
    const Eigen::Matrix3d r = ObjectFromPhotoCameraRotation({30.0, phi, 20.0});
    const OmegaPhiKappa b = OmegaPhiKappaFromRotation(r);
    EXPECT_NEAR(b.phi_deg, phi, 1e-6);
    EXPECT_EQ(b.kappa_deg, 0.0);
    EXPECT_LT((ObjectFromPhotoCameraRotation(b) - r).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(PhotogrammetricOrientationTest, PoseRoundTripsThroughThePhotogrammetricForm) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    Rigid3d pose;
    pose.rotation = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    pose.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1e6;
    const Eigen::Matrix3d r = PhotoCameraToWorldRotation(pose);
    EXPECT_TRUE(IsRotationMatrix(r));
    const Eigen::Vector3d centre = pose.Inverse().translation;
    const Rigid3d back =
        CamFromWorldFromPhotogrammetric(ObjectFromPhotoCameraRotation(OmegaPhiKappaFromRotation(r)), centre);
    // Same mapping of world points (up to sign of the quaternion).
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e6, -2e6, 300)}) {
      ExpectVectorNear(back * x, pose * x, 1e-6);
    }
  }
}

TEST(PhotogrammetricOrientationTest, RotationCheck) {
  EXPECT_TRUE(IsRotationMatrix(Eigen::Matrix3d::Identity()));
  EXPECT_FALSE(IsRotationMatrix(Eigen::Vector3d(1, 1, -1).asDiagonal().toDenseMatrix()));  // reflection
  EXPECT_FALSE(IsRotationMatrix(2.0 * Eigen::Matrix3d::Identity()));
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(1, 2) = std::nan("");
  EXPECT_FALSE(IsRotationMatrix(nan));
}

}  // namespace
}  // namespace sacfuse
