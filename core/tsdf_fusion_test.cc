// tsdf ([7]): a plane seen by nadir views becomes points on the plane within a small fraction of a voxel, one
// per voxel column; colours and source ids come from the most precise view; the voxel memory is bounded.
#include "core/tsdf_fusion.h"

#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/method_test_scene.h"
#include "core/sac_test_scene.h"
#include "tests/support/error_of.h"

namespace sacfuse {
namespace {

using testing::CollectingSink;
using testing::kEast;
using testing::kGroundZ;
using testing::kNorth;
using testing::NadirView;
using testing::PlaneDepth;
using Block = testing::MethodBlock;

constexpr double kHeight = 500.0;
constexpr double kGsd = kHeight / 3000.0;  // 1/6 m

TEST(TsdfFusionTest, APlaneBecomesOnePointPerVoxelColumnOnThePlane) {
  Block block;
  for (uint32_t i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + i * 4.0, kNorth + i * 1.5, kHeight);
    block.Add(v, PlaneDepth(v), testing::UniformImage(PlaneDepth(v), 10, 20, static_cast<uint8_t>(100 + i)));
  }
  const auto views = block.SacViews();
  ASSERT_NEAR(MedianGsdFromDepth(views), kGsd, 1e-6);
  CollectingSink sink;
  const FusionStats stats = RunTsdfFusion(views, TsdfOptions{}, sink);  // voxel = 1 GSD, truncation 8
  ASSERT_GT(sink.points().size(), 3000u);
  std::set<std::pair<long, long>> columns;
  for (const FusedPoint& p : sink.points()) {
    EXPECT_NEAR(p.point_in_world.z(), kGroundZ, 0.01 * kGsd);  // a hundredth of a voxel
    columns.emplace(std::lround(p.point_in_world.x() / kGsd - 0.5), std::lround(p.point_in_world.y() / kGsd - 0.5));
  }
  EXPECT_EQ(columns.size(), sink.points().size());  // no duplicates: one crossing per voxel column
  EXPECT_EQ(stats.emitted, sink.points().size());
  // Nadir views at one height see the plane at one depth: equal precision, so the view integrated first that
  // observed a voxel keeps it (view 0 over its footprint, view 1 beyond it).
  size_t from_0 = 0, from_1 = 0;
  for (const FusedPoint& p : sink.points()) {
    const double x = p.point_in_world.x() - kEast, y = p.point_in_world.y() - kNorth;
    const bool in_0 = std::abs(x) < 9.5 && std::abs(y) < 7.0;
    const bool out_0 = std::abs(x) > 10.5 || std::abs(y) > 8.0;
    const bool in_1 = std::abs(x - 4.0) < 9.5 && std::abs(y - 1.5) < 7.0;
    if (in_0) {
      ++from_0;
      EXPECT_EQ(p.view_index, 0u);
      EXPECT_EQ(p.rgb[2], 100);
    } else if (out_0 && in_1) {
      ++from_1;
      EXPECT_EQ(p.view_index, 1u);
      EXPECT_EQ(p.rgb[2], 101);
    }
  }
  EXPECT_GT(from_0, 1000u);
  EXPECT_GT(from_1, 100u);
}

TEST(TsdfFusionTest, SourceAndColourComeFromTheMostPreciseObservingView) {
  Block block;
  const View high = NadirView(0, kEast, kNorth, kHeight);
  const View high2 = NadirView(1, kEast + 3.0, kNorth, kHeight);
  const View low = NadirView(2, kEast + 1.0, kNorth, kHeight / 2);  // z^2/f a quarter of the others'
  block.Add(high, PlaneDepth(high), testing::UniformImage(PlaneDepth(high), 1, 0, 0));
  block.Add(high2, PlaneDepth(high2), testing::UniformImage(PlaneDepth(high2), 2, 0, 0));
  block.Add(low, PlaneDepth(low), testing::UniformImage(PlaneDepth(low), 3, 0, 0));
  CollectingSink sink;
  RunTsdfFusion(block.SacViews(), TsdfOptions{}, sink, kGsd);
  size_t inside_low = 0;
  for (const FusedPoint& p : sink.points()) {
    const double dx = p.point_in_world.x() - (kEast + 1.0), dy = p.point_in_world.y() - kNorth;
    if (std::abs(dx) < 5.0 - 0.5 && std::abs(dy) < 3.75 - 0.5) {  // well inside the low view's 10 x 7.5 m
      ++inside_low;
      EXPECT_EQ(p.view_index, 2u);
      EXPECT_EQ(p.rgb[0], 3);
    } else if (std::abs(dx) > 5.0 + 0.5 || std::abs(dy) > 3.75 + 0.5) {
      EXPECT_NE(p.view_index, 2u);
    }
  }
  EXPECT_GT(inside_low, 1000u);
}

TEST(TsdfFusionTest, VoxelMemoryIsBoundedAndOptionsAreValidated) {
  Block block;
  const View v = NadirView(0, kEast, kNorth, kHeight);
  block.Add(v, PlaneDepth(v));
  TsdfOptions tiny;
  tiny.max_memory_gb = 1e-4;  // ~100 kB: a few blocks
  CollectingSink sink;
  const std::string memory = testing::ErrorOf<Error>([&] { RunTsdfFusion(block.SacViews(), tiny, sink, kGsd); });
  EXPECT_NE(memory.find("tsdf.max_memory_gb"), std::string::npos) << memory;
  TsdfOptions bad;
  bad.truncation_gsd = 0.5;  // not more than the voxel
  bad.min_weight = 0;
  const std::string what = testing::OptionErrorOf([&] { ValidateTsdfOptions(bad); });
  EXPECT_NE(what.find("TsdfOptions.truncation_gsd = 0.5"), std::string::npos) << what;
  EXPECT_NE(what.find("TsdfOptions.min_weight = 0"), std::string::npos) << what;
}

}  // namespace
}  // namespace sacfuse
