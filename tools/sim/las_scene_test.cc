#include "tools/sim/las_scene.h"

#include <cmath>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "io/las_reader.h"
#include "tests/support/test_support.h"
#include "tools/sim/simulate.h"

namespace sacfuse::sim {
namespace {

std::string ZurichLas() {
  const auto shared = testing::SharedDir();
  if (!shared) return "";
  const auto path = *shared / "research-data/lidar/lastools/zurich.las";
  return std::filesystem::is_regular_file(path) ? path.string() : "";
}

TEST(LasSceneTest, ZurichDsmCropped) {
  const std::string path = ZurichLas();
  if (path.empty()) GTEST_SKIP() << "shared research data (lidar/lastools/zurich.las) not available";
  LasSceneOptions o;
  o.path = path;
  o.area_width_m = o.area_height_m = 40.0;
  const LasScene scene(o);
  EXPECT_NEAR(scene.area().Width(), 40.0, 1e-9);
  EXPECT_NEAR(scene.area().Height(), 40.0, 1e-9);
  LasHeader header;
  {
    LasReader reader(path);
    header = reader.header();
  }
  EXPECT_NEAR(scene.area().Center().x(), 0.5 * (header.min.x() + header.max.x()), 1e-6);
  EXPECT_GT(scene.ground_z(), header.min.z() - 1e-6);
  EXPECT_LT(scene.ground_z(), header.max.z());
  std::set<int> classes;
  for (double y = scene.area().min.y() + 0.5; y < scene.area().max.y(); y += 1.0) {
    for (double x = scene.area().min.x() + 0.5; x < scene.area().max.x(); x += 1.0) {
      const double z = scene.Height(x, y);
      ASSERT_TRUE(std::isfinite(z));
      EXPECT_GE(z, header.min.z() - 1e-3);
      EXPECT_LE(z, header.max.z() + 1e-3);
      classes.insert(scene.Class(x, y));
      const HeightRange r = scene.RangeOver(Box2d{x - 0.5, y - 0.5, x + 0.5, y + 0.5});
      EXPECT_LE(r.lo, z + 1e-3);
      EXPECT_GE(r.hi, z - 1e-3);
    }
  }
  EXPECT_TRUE(classes.count(2) || classes.count(6)) << "ground or building classes expected";
  EXPECT_TRUE(std::isnan(scene.Height(header.max.x() + 100.0, header.max.y() + 100.0)));
}

TEST(LasSceneTest, SimulateFromZurich) {
  const std::string path = ZurichLas();
  if (path.empty()) GTEST_SKIP() << "shared research data (lidar/lastools/zurich.las) not available";
  testing::TempDir dir;
  SimOptions o = SimPreset("tiny");
  o.scene = "las";
  o.from_las = path;
  o.area_width_m = o.area_height_m = 40.0;
  o.max_oblique_views = 8;
  const SimSummary s = SimulateBlock(o, dir.path().string());
  EXPECT_GT(s.num_views, 5);
  EXPECT_GT(s.depth_pixels, 0u);
  LasHeader header;
  const std::vector<LasPoint> ref = ReadAllLasPoints(s.reference_las, &header);
  ASSERT_EQ(ref.size(), s.reference_points);
  ASSERT_GT(ref.size(), 1000u);
  LasHeader source;
  { source = LasReader(path).header(); }
  const double cx = 0.5 * (source.min.x() + source.max.x()), cy = 0.5 * (source.min.y() + source.max.y());
  for (const LasPoint& p : ref) {
    ASSERT_LE(std::abs(p.xyz.x() - cx), 20.0 + 1e-6);
    ASSERT_LE(std::abs(p.xyz.y() - cy), 20.0 + 1e-6);
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(s.eval_mask_png));
}

}  // namespace
}  // namespace sacfuse::sim
