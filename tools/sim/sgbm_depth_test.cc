// Matcher-made depth maps (`sacfuse simulate --depth sgbm`): the rectification's geometry, the pair merge, one
// pair matched on a rendered scene against its true depth, and a whole tiny block.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "io/colmap_workspace.h"
#include "tests/support/test_support.h"
#include "tools/sim/city_layout.h"
#include "tools/sim/city_scene.h"
#include "tools/sim/flight_plan.h"
#include "tools/sim/pair_merge.h"
#include "tools/sim/render.h"
#include "tools/sim/sgbm_pair.h"
#include "tools/sim/simulate.h"
#include "tools/sim/stereo_rectify.h"

namespace sacfuse::sim {
namespace {

namespace fs = std::filesystem;

constexpr double kGround = 100.0;

Rigid3d PoseAt(const Eigen::Vector3d& center, const Eigen::Vector2d& toward, double tilt_deg) {
  const Rigid3d world_from_cam{Eigen::Quaterniond(WorldFromCameraRotation(toward, tilt_deg * M_PI / 180.0)), center};
  return world_from_cam.Inverse();
}

// A world point's position on a canvas, via the inverse of the canvas -> image homography.
Eigen::Vector2d OnCanvas(const PinholeCamera& camera, const Rigid3d& pose, const Eigen::Matrix3d& canvas_to_image,
                         const Eigen::Vector3d& world) {
  const Eigen::Vector2d uv = camera.Project(pose * world);
  const Eigen::Vector3d q = canvas_to_image.inverse() * Eigen::Vector3d(uv.x() - 0.5, uv.y() - 0.5, 1.0);
  return q.head<2>() / q.z();
}

// Every point of a grid at three heights lands on one canvas row in both views, at the disparity its rectified depth
// gives: baseline along the image rows, along the columns, and two 45-degree obliques a station apart.
TEST(StereoRectifyTest, PointsShareARowAndTheirDisparityGivesTheirDepth) {
  const PinholeCamera cam = PinholeCamera::Centered(400, 300, 500.0);
  struct Layout {
    const char* name;
    Rigid3d ref, src;
  };
  const Layout layouts[] = {
      {"along the rows", PoseAt({0, 0, kGround + 120}, {0, 1}, 0.0), PoseAt({30, 1, kGround + 121}, {0, 1}, 0.0)},
      {"along the columns", PoseAt({0, 0, kGround + 120}, {0, 1}, 0.0), PoseAt({1, -35, kGround + 119}, {0, 1}, 0.0)},
      {"obliques", PoseAt({0, -120, kGround + 120}, {0, 1}, 45.0), PoseAt({40, -120, kGround + 121}, {0, 1}, 45.0)},
  };
  for (const Layout& l : layouts) {
    const RectifiedPair pair = RectifyPair(cam, l.ref, cam, l.src, 60.0, 250.0, 512);
    EXPECT_EQ(pair.num_disparities % 16, 0) << l.name;
    EXPECT_NEAR(pair.rect_from_ref.determinant(), 1.0, 1e-12) << l.name;
    int tested = 0;
    for (double x = -20; x <= 20; x += 10) {
      for (double y = -15; y <= 15; y += 10) {
        for (double z : {0.0, 10.0, 25.0}) {
          const Eigen::Vector3d world(x, y, kGround + z);
          const Eigen::Vector3d in_ref = l.ref * world;
          const Eigen::Vector2d left = OnCanvas(cam, l.ref, pair.left_to_ref, world);
          const Eigen::Vector2d right = OnCanvas(cam, l.src, pair.right_to_src, world);
          const double z_rect = (pair.rect_from_ref * in_ref).z();
          EXPECT_NEAR(left.y(), right.y(), 1e-6) << l.name;
          EXPECT_NEAR(pair.RectifiedDepth(left.x() - right.x()), z_rect, 1e-6 * z_rect) << l.name;
          EXPECT_GT(left.x() - right.x(), 0.0) << l.name;
          EXPECT_LT(left.x() - right.x(), pair.num_disparities) << l.name;
          ++tested;
        }
      }
    }
    EXPECT_EQ(tested, 60) << l.name;
  }
}

TEST(PairMergeTest, MedianOfTheAgreeingPairsWhereEnoughAgree) {
  // Four pairs, four pixels: three agree of four valid; one valid; none; two far apart.
  std::vector<DepthMap> pairs(4, DepthMap(4, 1, 1, 0.0f));
  const float values[4][4] = {{10.0f, 7.0f, 0.0f, 20.0f}, {10.05f, 0.0f, 0.0f, 30.0f}, {12.0f, 0.0f, 0.0f, 0.0f},
                              {10.02f, 0.0f, 0.0f, 0.0f}};
  for (int p = 0; p < 4; ++p) {
    for (int px = 0; px < 4; ++px) pairs[p].data[px] = values[p][px];
  }
  const PairMerge two = MergePairDepths(pairs, 0.01, 2);
  // Valid {10, 10.05, 12, 10.02}: median 10.035; 12 disagrees; the median of the other three is 10.02.
  EXPECT_FLOAT_EQ(two.depth.data[0], 10.02f);
  EXPECT_EQ(two.agreeing[0], 3);
  EXPECT_EQ(two.depth.data[1], 0.0f);  // one pair only
  EXPECT_EQ(two.agreeing[1], 1);
  EXPECT_EQ(two.depth.data[2], 0.0f);
  EXPECT_EQ(two.agreeing[2], 0);
  EXPECT_EQ(two.depth.data[3], 0.0f);  // 20 and 30: median 25, neither within 1 %
  const PairMerge one = MergePairDepths(pairs, 0.01, 1);
  EXPECT_FLOAT_EQ(one.depth.data[1], 7.0f);  // single-pair depths kept
  EXPECT_EQ(one.depth.data[3], 0.0f);
  EXPECT_THROW(MergePairDepths({DepthMap(2, 2), DepthMap(3, 2)}, 0.01, 1), std::invalid_argument);
}

cv::Mat Grey(const RgbImage& image) {
  cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.data.data()));
  cv::Mat grey;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  return grey;
}

// Two nadir views of the procedural city with exact poses: the matched depth lies on the rendered truth (a median
// within 0.3 % of the depth, a fifth of a pixel of disparity), without a bias, from either view of the pair.
TEST(SgbmPairTest, MatchedDepthFollowsTheTruth) {
  CityParams p;
  p.area_width_m = p.area_height_m = 80.0;
  p.center_x = 390040.0;
  p.center_y = 5705040.0;
  p.ground_z = kGround;
  p.seed = 3;
  const CityScene city(GenerateCityLayout(p));
  const PinholeCamera cam = PinholeCamera::Centered(320, 240, 600.0);
  const Rigid3d a = PoseAt({p.center_x - 9, p.center_y, kGround + 120}, {0, 1}, 0.0);
  const Rigid3d b = PoseAt({p.center_x + 9, p.center_y + 1, kGround + 120.5}, {0, 1}, 0.0);
  for (const auto& [ref, src] : {std::pair{a, b}, std::pair{b, a}}) {
    RenderRequest r;
    r.surface = &city;
    r.camera = cam;
    r.cam_from_world = ref;
    const RenderedView ref_view = RenderView(r);
    r.cam_from_world = src;
    const RenderedView src_view = RenderView(r);
    const RectifiedPair pair = RectifyPair(cam, ref, cam, src, 70.0, 140.0, 256);
    const PairDepthResult matched =
        MatchPair(Grey(ref_view.image), cam, Grey(src_view.image), pair, SgbmMatchOptions{});
    ASSERT_EQ(matched.depth.width, cam.width);
    EXPECT_GT(matched.valid_fraction, 0.5);
    std::vector<double> relative, signed_error;
    for (size_t i = 0; i < matched.depth.num_pixels(); ++i) {
      const float d = matched.depth.data[i], t = ref_view.depth.data[i];
      if (!IsValidDepth(d) || !IsValidDepth(t)) continue;
      relative.push_back(std::abs(d - t) / t);
      signed_error.push_back(d - t);
    }
    ASSERT_GT(relative.size(), cam.width * cam.height / 2u);
    std::nth_element(relative.begin(), relative.begin() + relative.size() / 2, relative.end());
    std::nth_element(signed_error.begin(), signed_error.begin() + signed_error.size() / 2, signed_error.end());
    EXPECT_LT(relative[relative.size() / 2], 0.003);
    EXPECT_LT(std::abs(signed_error[signed_error.size() / 2]), 0.05);  // metres, at 100-120 m
  }
}

// The whole tiny block with matched depth maps: every view has a depth map of the image's size whose valid depths
// lie near the true surface, and the metadata records the matcher's sources and errors. The obliques' depth is
// biased by the block's pose errors (5 cm on baselines of ~25 m: 0.4-0.9 m at 130-150 m; without pose errors their
// medians are within 0.17 m), as a real pipeline's is.
TEST(SgbmBlockTest, TinyBlockWithMatchedDepthMaps) {
  testing::TempDir dir;
  SimOptions o = SimPreset("tiny");
  o.depth = "sgbm";
  o.write_consistency_graphs = false;
  const SimSummary s = SimulateBlock(o, dir.path().string());
  EXPECT_EQ(s.num_views, 20);
  const nlohmann::json meta = nlohmann::json::parse(testing::ReadFileBytes(dir.path() / "metadata.json"));
  ASSERT_EQ(meta["depth_mode"], "sgbm");
  ASSERT_EQ(meta["sgbm"]["views"].size(), 20u);
  EXPECT_GT(meta["sgbm"]["pairs"].get<int>(), 40);
  const ColmapWorkspace ws(dir.path().string(), ColmapDepthType::kGeometric);
  uint64_t valid = 0, total = 0;
  for (const View& v : ws.views()) {
    const auto& jv = meta["sgbm"]["views"][v.index];
    EXPECT_EQ(jv["name"], v.name);
    EXPECT_GE(jv["sources"].size(), 1u) << v.name;
    // patch-match.cfg names the same sources: they are the view's matching partners (independent support).
    for (const auto& source : jv["sources"]) {
      const auto it = std::find_if(ws.views().begin(), ws.views().end(),
                                   [&](const View& u) { return u.name == source.get<std::string>(); });
      ASSERT_NE(it, ws.views().end());
      EXPECT_TRUE(std::binary_search(v.matching_partners.begin(), v.matching_partners.end(), it->index)) << v.name;
    }
    const bool nadir = v.name.rfind("nadir/", 0) == 0;
    EXPECT_LT(jv["median_abs_error_m"].get<double>(), nadir ? 0.2 : 1.0) << v.name;  // 1 / 5 GSD
    const DepthMap depth = ws.ReadDepthMap(v);
    ASSERT_EQ(depth.width, v.camera.width);
    for (const float d : depth.data) valid += IsValidDepth(d) ? 1 : 0;
    total += depth.num_pixels();
  }
  EXPECT_EQ(valid, s.depth_pixels);
  EXPECT_GT(static_cast<double>(valid) / total, 0.2);  // 0.27: few pairs per view at tiny's 60 / 50 % overlap
  EXPECT_LT(static_cast<double>(valid) / total, 0.95);
}

}  // namespace
}  // namespace sacfuse::sim
