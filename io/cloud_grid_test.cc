// Gridding cloud files (io/cloud_grid.h, io/point_cloud_file.h): LAS and PLY give the cells' known heights, and
// gridding in bands of rows (bounded memory) equals gridding at once.
#include "io/cloud_grid.h"

#include <cmath>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "io/las_writer.h"
#include "io/point_cloud_file.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

std::vector<FusedPoint> RandomPoints(size_t n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(0.0, 20.0), z(100.0, 130.0);
  std::vector<FusedPoint> points(n);
  for (FusedPoint& p : points) p.point_in_world = {500000.0 + xy(rng), 5700000.0 + xy(rng), z(rng)};
  return points;
}

TEST(CloudGridTest, BandsOfRowsEqualOneGriddingAndKeepFiltersClasses) {
  testing::TempDir dir;
  const std::string las = (dir / "cloud.laz").string();
  const std::vector<FusedPoint> points = RandomPoints(20000);
  {
    LasWriterOptions o;
    o.compressed = true;
    LasWriter w(las, o);
    w.Write(points.data(), points.size());
    w.Close();
  }
  PointCloudFile cloud(las);
  EXPECT_TRUE(cloud.is_las());
  EXPECT_EQ(cloud.point_count(), points.size());
  const CellWindow extent = CellWindowCovering(cloud.bounds_xy(), 0.5);
  CloudGridOptions once;
  once.quantile = 0.9;
  const CloudGrid a = GridCloud(cloud, extent, once);
  CloudGridOptions banded = once;
  banded.max_points_in_memory = 1500;  // ~14 bands
  const CloudGrid b = GridCloud(cloud, extent, banded);
  EXPECT_EQ(a.passes, 1);
  EXPECT_GT(b.passes, 10);
  EXPECT_EQ(a.points_gridded, points.size());
  EXPECT_EQ(b.points_gridded, points.size());
  ASSERT_EQ(a.values.size(), b.values.size());
  for (size_t i = 0; i < a.values.size(); ++i) {
    ASSERT_TRUE((std::isnan(a.values[i]) && std::isnan(b.values[i])) || a.values[i] == b.values[i]) << i;
  }
  CloudGridOptions none = once;
  none.keep = [](uint8_t c) { return c != 0; };  // every point here is class 0
  EXPECT_EQ(GridCloud(cloud, extent, none).points_gridded, 0u);
}

TEST(CloudGridTest, PlyCloudsWithAShiftGridLikeLas) {
  testing::TempDir dir;
  const std::string ply = (dir / "cloud.ply").string();
  {
    std::ofstream out(ply, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nend_header\n";
    const float v[3][3] = {{0.25f, 0.25f, 1.0f}, {0.75f, 0.25f, 3.0f}, {1.25f, 0.75f, 2.0f}};
    out.write(reinterpret_cast<const char*>(v), sizeof(v));
  }
  PointCloudFile cloud(ply, Eigen::Vector3d(1000.0, 2000.0, 10.0));
  EXPECT_FALSE(cloud.is_las());
  EXPECT_TRUE(cloud.crs_wkt().empty());
  const Box2d b = cloud.bounds_xy();
  EXPECT_DOUBLE_EQ(b.min.x(), 1000.25);
  const CellWindow w = CellWindowCovering(b, 1.0);
  const CloudGrid g = GridCloud(cloud, w, CloudGridOptions{});
  EXPECT_EQ(w.cols, 2);
  EXPECT_FLOAT_EQ(g.values[w.Index(1000, 2000)], 13.0f);  // the highest of the first cell's two points
  EXPECT_FLOAT_EQ(g.values[w.Index(1001, 2000)], 12.0f);
}

}  // namespace
}  // namespace sacfuse
