#include "core/coregistration.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"

namespace sacfuse {
namespace {

// A scene known exactly: the ground z = 0 with box buildings (their walls and roofs are what fix a view's
// horizontal position), at UTM-sized coordinates.
constexpr double kEast0 = 390000.0, kNorth0 = 5705000.0;

struct Box3 {
  Eigen::Vector3d lo, hi;
};

std::vector<Box3> Buildings() {
  std::vector<Box3> b;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double x = kEast0 - 12 + 7.5 * i, y = kNorth0 - 9 + 7.0 * j;
      b.push_back({{x, y, 0.0}, {x + 3.0 + 0.5 * i, y + 2.5 + 0.7 * j, 2.0 + 1.3 * ((i + j) % 3)}});
    }
  }
  return b;
}

// Ray parameter of the first hit of centre + t dir (t > 0), infinity when none.
double Hit(const Eigen::Vector3d& c, const Eigen::Vector3d& d, const std::vector<Box3>& boxes) {
  double best = d.z() < 0 ? -c.z() / d.z() : std::numeric_limits<double>::infinity();
  for (const Box3& b : boxes) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double a = (b.lo[k] - c[k]) / d[k], e = (b.hi[k] - c[k]) / d[k];
      t0 = std::max(t0, std::min(a, e));
      t1 = std::min(t1, std::max(a, e));
    }
    if (t0 <= t1 && t0 < best) best = t0;
  }
  return best;
}

// A camera at (east, north, 60 m) looking down, tilted by `tilt_deg` about the world x axis.
View Camera(uint32_t index, double east, double north, double tilt_deg) {
  View v;
  v.index = index;
  v.name = std::to_string(index);
  v.camera = PinholeCamera::Centered(240, 180, 600.0);  // GSD 0.1 m at 60 m
  const Eigen::Matrix3d down = (Eigen::Matrix3d() << 1, 0, 0, 0, -1, 0, 0, 0, -1).finished();
  const Eigen::Matrix3d world_from_cam = Eigen::AngleAxisd(tilt_deg * M_PI / 180.0, Eigen::Vector3d::UnitX()) * down;
  const Rigid3d pose{Eigen::Quaterniond(world_from_cam), Eigen::Vector3d(east, north, 60.0)};
  v.cam_from_world = pose.Inverse();
  return v;
}

DepthMap Render(const View& v, const std::vector<Box3>& boxes) {
  DepthMap depth(v.camera.width, v.camera.height, 1, 0.0f);
  const Rigid3d world_from_cam = v.cam_from_world.Inverse();
  for (int r = 0; r < depth.height; ++r) {
    for (int c = 0; c < depth.width; ++c) {
      const Eigen::Vector3d d = world_from_cam.rotation * v.camera.Unproject(c + 0.5, r + 0.5, 1.0);
      const double t = Hit(world_from_cam.translation, d, boxes);
      if (std::isfinite(t)) depth.at(r, c) = static_cast<float>(t);  // z-depth: the ray has camera z = 1
    }
  }
  return depth;
}

// Nine nadir views and four 30-degree obliques, rendered with their true poses.
std::vector<CoregistrationInput> TrueBlock() {
  const std::vector<Box3> boxes = Buildings();
  std::vector<View> views;
  for (int i = 0; i < 9; ++i) views.push_back(Camera(i, kEast0 - 4 + 4 * (i % 3), kNorth0 - 4 + 4 * (i / 3), 0.0));
  views.push_back(Camera(9, kEast0, kNorth0 - 30, 30.0));
  views.push_back(Camera(10, kEast0, kNorth0 + 30, -30.0));
  views.push_back(Camera(11, kEast0 + 4, kNorth0 - 28, 28.0));
  views.push_back(Camera(12, kEast0 - 4, kNorth0 + 28, -28.0));
  std::vector<CoregistrationInput> block;
  for (const View& v : views) block.push_back({v, v.camera, Render(v, boxes)});
  return block;
}

// The block with written poses off the rendering ones: each view's points rotated about where its principal ray
// meets the ground and shifted, rotations and shifts of zero mean (so the datum co-registration keeps is the true
// one).
std::vector<CoregistrationInput> PerturbedBlock(double rotation_deg, double shift_m) {
  std::vector<CoregistrationInput> block = TrueBlock();
  const size_t n = block.size();
  std::vector<Eigen::Vector3d> rot(n), shift(n);
  Eigen::Vector3d mean_rot = Eigen::Vector3d::Zero(), mean_shift = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < n; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    const Eigen::Vector3d axis(std::cos(k * 1.3), std::sin(k * 1.3), 0.3 * sign);
    rot[k] = rotation_deg * M_PI / 180.0 * axis.normalized();
    shift[k] = shift_m * Eigen::Vector3d(std::cos(k * 2.1), std::sin(k * 2.1), 0.5 * sign);
    mean_rot += rot[k] / static_cast<double>(n);
    mean_shift += shift[k] / static_cast<double>(n);
  }
  for (size_t k = 0; k < n; ++k) {
    const Rigid3d world_from_cam = block[k].view.cam_from_world.Inverse();
    const Eigen::Vector3d c = world_from_cam.translation, d = world_from_cam.rotation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d ground = c - c.z() / d.z() * d;
    const Eigen::Vector3d w = rot[k] - mean_rot;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(w.norm(), w.normalized()));
    const Rigid3d error{q, ground + shift[k] - mean_shift - q * ground};
    block[k].view.cam_from_world = (error * world_from_cam).Inverse();
  }
  return block;
}

// RMS distance between each view's pixels back-projected with `poses` and with the true poses, metres.
double PoseErrorRms(const std::vector<CoregistrationInput>& truth, const std::vector<Rigid3d>& poses) {
  double ss = 0.0;
  size_t n = 0;
  for (size_t k = 0; k < truth.size(); ++k) {
    const DepthMap& d = truth[k].depth;
    for (int r = 0; r < d.height; r += 5) {
      for (int c = 0; c < d.width; c += 5) {
        if (!IsValidDepth(d.at(r, c))) continue;
        const Eigen::Vector3d p = truth[k].depth_camera.Unproject(c + 0.5, r + 0.5, d.at(r, c));
        ss += (poses[k].Inverse() * p - truth[k].view.cam_from_world.Inverse() * p).squaredNorm();
        ++n;
      }
    }
  }
  return std::sqrt(ss / static_cast<double>(n));
}

std::vector<Rigid3d> PosesOf(const std::vector<CoregistrationInput>& block) {
  std::vector<Rigid3d> p;
  for (const auto& in : block) p.push_back(in.view.cam_from_world);
  return p;
}

std::vector<Rigid3d> PosesOf(const CoregistrationResult& result) {
  std::vector<Rigid3d> p;
  for (const auto& v : result.views) p.push_back(v.cam_from_world);
  return p;
}

TEST(CoregistrationTest, RecoversPoseErrorsOfZeroMean) {
  const std::vector<CoregistrationInput> truth = TrueBlock();
  const std::vector<CoregistrationInput> block = PerturbedBlock(0.15, 0.3);
  const double before = PoseErrorRms(truth, PosesOf(block));
  CoregistrationOptions options;
  options.iterations = 15;
  const CoregistrationResult result = Coregister(block, options);
  const double after = PoseErrorRms(truth, PosesOf(result));
  EXPECT_GT(before, 0.25);
  EXPECT_LT(after, 0.05 * before) << "before " << before << " m, after " << after << " m";
  ASSERT_EQ(result.iterations.size(), 16u);
  EXPECT_LT(result.iterations.back().weighted_rms_m, 0.5 * result.iterations.front().weighted_rms_m);
  for (const ViewCorrection& v : result.views) {
    EXPECT_GT(v.samples, 1000u);
    EXPECT_GT(v.residuals_before, 0u);
    EXPECT_LT(v.rms_after_m, v.rms_before_m);
    EXPECT_GT(v.rotation_deg, 0.0);
  }
}

// Exact poses stay within a fraction of a GSD (0.1 m here): what is left is the discretisation of the rendered
// depth maps (pixel-centre lookups at roof edges and wall feet leave 3-6 cm residuals even at the true poses, and
// the steps drift a little along what the data hardly fix: 0.2 degrees turn a 12 m footprint's edge by 4 cm).
TEST(CoregistrationTest, LeavesExactPosesAlone) {
  const std::vector<CoregistrationInput> truth = TrueBlock();
  const CoregistrationResult result = Coregister(truth, CoregistrationOptions{});
  EXPECT_LT(PoseErrorRms(truth, PosesOf(result)), 0.015);
  for (const ViewCorrection& v : result.views) {
    EXPECT_LT(v.rotation_deg, 0.2);
    EXPECT_LT(v.shift_m.norm(), 0.02);
  }
}

TEST(CoregistrationTest, KeepsTheBlockDatum) {
  // Every view shifted by the same 1 m: the depth maps agree with each other, so nothing is corrected (the common
  // shift is the georeference's, which co-registration cannot see and must not move).
  std::vector<CoregistrationInput> block = TrueBlock();
  for (auto& in : block) {
    const Rigid3d moved{Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.0, 0.0, 0.0)};
    in.view.cam_from_world = (moved * in.view.cam_from_world.Inverse()).Inverse();  // the camera 1 m east
  }
  const CoregistrationResult result = Coregister(block, CoregistrationOptions{});
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const ViewCorrection& v : result.views) mean += v.shift_m / static_cast<double>(result.views.size());
  EXPECT_LT(mean.norm(), 0.002);
  EXPECT_LT(PoseErrorRms(block, PosesOf(result)), 0.015);
}

TEST(CoregistrationTest, SameResultForAnyThreadCount) {
  const std::vector<CoregistrationInput> block = PerturbedBlock(0.1, 0.2);
  CoregistrationResult one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = Coregister(block, CoregistrationOptions{});
  }
  many = Coregister(block, CoregistrationOptions{});
  for (size_t k = 0; k < block.size(); ++k) {
    EXPECT_EQ(one.views[k].cam_from_world.rotation.coeffs(), many.views[k].cam_from_world.rotation.coeffs());
    EXPECT_EQ(one.views[k].cam_from_world.translation, many.views[k].cam_from_world.translation);
  }
}

TEST(CoregistrationTest, DecimationKeepsPixelCentres) {
  EXPECT_EQ(CoregistrationDecimation(800, 600, 480000), 1);
  EXPECT_EQ(CoregistrationDecimation(800, 600, 250000), 3);
  EXPECT_EQ(CoregistrationDecimation(8000, 6000, 250000), 15);
  DepthMap depth(7, 4, 1, 0.0f);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 7; ++c) depth.at(r, c) = static_cast<float>(10 * r + c);
  }
  const DepthMap d = DecimateDepth(depth, 3);
  ASSERT_EQ(d.width, 2);
  ASSERT_EQ(d.height, 1);
  EXPECT_EQ(d.at(0, 0), 11.0f);  // the centre pixel of each 3 x 3 block
  EXPECT_EQ(d.at(0, 1), 14.0f);
}

TEST(CoregistrationTest, DecimatingTheKeptRowsAloneGivesTheSameRaster) {
  DepthMap depth(47, 38, 1, 0.0f);
  for (size_t i = 0; i < depth.data.size(); ++i) depth.data[i] = static_cast<float>(i % 101) * 0.5f;
  for (const int k : {1, 3, 5, 15}) {
    SCOPED_TRACE(k);
    const std::vector<int> rows = DecimatedRows(depth.height, k);
    ASSERT_EQ(rows.size(), static_cast<size_t>(depth.height / k));
    DepthMap kept(depth.width, static_cast<int>(rows.size()), 1, 0.0f);
    for (size_t r = 0; r < rows.size(); ++r) {
      for (int c = 0; c < depth.width; ++c) kept.at(static_cast<int>(r), c) = depth.at(rows[r], c);
    }
    const DepthMap whole = DecimateDepth(depth, k);
    const DepthMap from_rows = DecimateDepthRows(kept, k);
    ASSERT_EQ(from_rows.width, depth.width / k);
    ASSERT_EQ(from_rows.height, depth.height / k);
    EXPECT_EQ(from_rows.data, whole.data);
    if (k == 3) EXPECT_EQ(whole.at(2, 4), depth.at(7, 13));  // pixel (k r + 1, k c + 1)
  }
}

TEST(CoregistrationTest, RejectsBadOptions) {
  CoregistrationOptions o;
  o.iterations = 0;
  o.huber_gsd = -1.0;
  try {
    ValidateCoregistrationOptions(o);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("iterations = 0"), std::string::npos) << m;
    EXPECT_NE(m.find("huber_gsd = -1"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace sacfuse
