// The cross-section's point sources: depth windows back-projected into the strip (nothing missed against
// back-projecting every pixel, far fewer pixels read) and LAS files streamed through it.
#include "report/report_profile_sources.h"

#include <gtest/gtest.h>

#include "core/backproject.h"
#include "io/las_writer.h"
#include "report/report_test_block.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

// A nadir view 100 m above ground (z = 0) with 1 m GSD, 200 x 160 px centred at (cx, 0); a 20 m x 20 m
// "building" (roof z = 10) at x, y in [0, 20].
DepthMap SceneDepth(const View& v) {
  const PinholeCamera& cam = v.camera;
  const Eigen::Vector3d center = v.CenterInWorld();
  DepthMap d(cam.width, cam.height);
  for (int r = 0; r < cam.height; ++r) {
    for (int c = 0; c < cam.width; ++c) {
      // The ray through the pixel centre hits z = 0 at ground_xy; over the roof it stops at z = 10.
      const double gx = center.x() + (c + 0.5 - cam.cx) / cam.fx * center.z();
      const double gy = center.y() - (r + 0.5 - cam.cy) / cam.fy * center.z();
      const bool roof = gx >= 0 && gx <= 20 && gy >= 0 && gy <= 20;
      d.at(r, c) = (r + c) % 9 == 0 ? 0.0f : static_cast<float>(roof ? center.z() - 10.0 : center.z());
    }
  }
  return d;
}

struct FullCount : PointSink {
  const ProfileStrip* strip = nullptr;
  uint64_t in_strip = 0;
  void Write(const FusedPoint* p, size_t n) override {
    for (size_t i = 0; i < n; ++i) in_strip += strip->Along(p[i].point_in_world.x(), p[i].point_in_world.y()) ? 1 : 0;
  }
};

TEST(ReportProfileSourcesTest, DepthWindowsGiveEveryPixelInTheStripAndReadLittle) {
  testing::MemoryDepthBlock block;
  for (const double cx : {-10.0, 30.0}) {
    View v = testing::NadirView("nadir/" + std::to_string(static_cast<int>(cx)) + ".jpg", cx, 0, 100, 200, 160, 100);
    const DepthMap d = SceneDepth(v);
    block.Add(v, d);
  }
  ProfileStrip strip;
  strip.start_xy = {-15.0, 10.2};
  strip.end_xy = {35.0, 10.2};
  strip.half_width_m = 1.0;
  strip.z_min_m = -2.0;
  strip.z_max_m = 12.0;

  ProfileSample sample(1000000);
  const DepthStripStats stats = SampleDepthInStrip(block, strip, &sample);
  EXPECT_EQ(stats.views_read, 2u);
  // Brute force: every valid pixel of both rasters back-projected.
  uint64_t expected = 0;
  for (const View& v : block.views()) {
    FullCount full;
    full.strip = &strip;
    BackprojectDepthMap(v, block.ReadDepthMap(v), nullptr, full);
    expected += full.in_strip;
  }
  EXPECT_EQ(sample.seen(), expected);
  EXPECT_GT(expected, 150u);  // ~2 rows of ~50 px per view
  EXPECT_LT(stats.window_pixels, 2u * 200u * 160u / 10u);  // a thin window, not the rasters
  // Both views contribute (source IDs 1 and 2), the roof at z = 10 and the ground at z = 0.
  bool id1 = false, id2 = false, roof = false, ground = false;
  for (const ProfilePoint& p : sample.points()) {
    id1 |= p.source_id == 1;
    id2 |= p.source_id == 2;
    roof |= std::abs(p.z_m - 10.0f) < 1e-3f && p.along_m > 15.0f && p.along_m < 35.0f;
    ground |= std::abs(p.z_m) < 1e-3f;
  }
  EXPECT_TRUE(id1 && id2 && roof && ground);
}

TEST(ReportProfileSourcesTest, LasPointsInTheStripAreSampledWithTheirSource) {
  testing::TempDir dir;
  const std::string a = (dir / "a.las").string(), b = (dir / "b.las").string();
  {
    LasWriter w(a, LasWriterOptions{});
    std::vector<FusedPoint> pts;
    for (int i = 0; i < 100; ++i) {
      FusedPoint p;
      p.point_in_world = {500000.0 + i, 5700000.0 + (i % 2 == 0 ? 0.05 : 3.0), 100.0 + i};
      p.view_index = 4;
      pts.push_back(p);
    }
    w.Write(pts.data(), pts.size());
    w.Close();
  }
  {
    LasWriter w(b, LasWriterOptions{});
    FusedPoint p;
    p.point_in_world = {500010.0, 5700100.0, 1.0};  // far from the strip: the file is skipped by its bounds
    w.Write(&p, 1);
    w.Close();
  }
  ProfileStrip strip;
  strip.start_xy = {500010.0, 5700000.0};
  strip.end_xy = {500060.0, 5700000.0};
  strip.half_width_m = 0.1;
  ProfileSample sample(1000);
  SampleLasInStrip({a, b}, strip, &sample);
  EXPECT_EQ(sample.seen(), 26u);  // even i in [10, 60]
  for (const ProfilePoint& p : sample.points()) {
    EXPECT_EQ(p.source_id, 5);
    EXPECT_NEAR(p.z_m - 100.0f, p.along_m + 10.0f, 1e-3f);
  }
  ProfileSample reference(1000);
  SampleLasInStrip({a}, strip, &reference, /*keep_source_id=*/false);
  EXPECT_EQ(reference.points().front().source_id, 0);
  EXPECT_THROW(SampleLasInStrip({(dir / "missing.las").string()}, strip, &sample), Error);
}

}  // namespace
}  // namespace sacfuse
