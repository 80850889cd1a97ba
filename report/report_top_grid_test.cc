// The report's top grid: topmost point and its source per cell, cell placement, sizing.
#include "report/report_top_grid.h"

#include <random>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

namespace sacfuse {
namespace {

TEST(ReportTopGridTest, KeepsTheTopmostPointAndItsSourcePerCell) {
  TopGrid g(100.0, 200.0, 1.0, 4, 3);  // x in [100, 104), y in (197, 200]
  EXPECT_TRUE(g.Add(100.5, 199.5, 10.0, 1));
  EXPECT_TRUE(g.Add(100.7, 199.2, 12.0, 2));  // same cell, higher: wins
  EXPECT_TRUE(g.Add(100.2, 199.9, 11.0, 3));  // same cell, lower: counted only
  EXPECT_TRUE(g.Add(103.5, 197.5, 5.0, 7));   // south-east corner cell
  EXPECT_FALSE(g.Add(104.0, 198.0, 1.0, 1));  // east of the grid
  EXPECT_FALSE(g.Add(101.0, 200.5, 1.0, 1));  // north of it
  const size_t nw = g.Index(0, 0), se = g.Index(2, 3);
  EXPECT_FLOAT_EQ(g.top_z[nw], 12.0f);
  EXPECT_EQ(g.source_id[nw], 2);
  EXPECT_EQ(g.count[nw], 3u);
  EXPECT_EQ(g.source_id[se], 7);
  EXPECT_TRUE(g.Empty(1, 1));
  EXPECT_DOUBLE_EQ(g.CellCenterX(3), 103.5);
  EXPECT_DOUBLE_EQ(g.CellCenterY(2), 197.5);
}

TEST(ReportTopGridTest, MadeGridHoldsBothEdgesOfTheBoxAndRespectsTheCap) {
  const TopGrid g = MakeTopGrid(500.0, 1000.0, 600.0, 1050.0, 1000000, 200, 0.05);
  EXPECT_LE(std::max(g.width, g.height), 200);
  for (const double x : {500.0, 600.0}) {
    for (const double y : {1000.0, 1050.0}) EXPECT_TRUE(g.CellOf(x, y).has_value()) << x << " " << y;
  }
  EXPECT_GE(g.cell_m, 100.0 / 199.0 - 1e-12);  // the cap decides: 100 m over at most 200 cells
}

TEST(ReportTopGridTest, CellSizeFollowsPointSpacingWhenSparse) {
  // 10,000 points over 100 m x 100 m: spacing 1 m, cells 2.5 m (the cap of 1000 cells would allow 0.1 m).
  EXPECT_NEAR(TopGridCellSize(100.0, 100.0, 10000, 1000, 0.05), 2.5, 1e-9);
  // Dense: the floor.
  EXPECT_NEAR(TopGridCellSize(10.0, 10.0, 100000000, 1000, 0.05), 0.05, 1e-9);
}

TEST(ReportTopGridTest, FillerGivesTheGridOfAddingPointByPointForAnyBandsAndThreads) {
  // 3 batches of 10,000 points (blocks of 4,096 cut across them), many on the same heights so that ties between
  // sources decide by order, some outside the grid.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> xy(-2.0, 42.0);
  std::uniform_int_distribution<int> z(0, 7), id(1, 9);
  std::vector<std::vector<LasPoint>> batches(3, std::vector<LasPoint>(10000));
  TopGrid serial(0.0, 40.0, 1.0, 40, 37);
  for (std::vector<LasPoint>& batch : batches) {
    for (LasPoint& p : batch) {
      p.xyz = {xy(rng), xy(rng), 0.5 * z(rng)};
      p.point_source_id = static_cast<uint16_t>(id(rng));
      serial.Add(p.xyz.x(), p.xyz.y(), p.xyz.z(), p.point_source_id);
    }
  }
  for (const int threads : {1, 3}) {
    for (const size_t bands : {size_t{1}, size_t{2}, size_t{7}, size_t{100}}) {
      TopGrid grid(0.0, 40.0, 1.0, 40, 37);
      tbb::task_arena(threads).execute([&] {
        TopGridFiller filler(&grid, bands);
        for (const std::vector<LasPoint>& batch : batches) filler.Add(batch);
      });
      EXPECT_EQ(grid.count, serial.count) << threads << " threads, " << bands << " bands";
      EXPECT_EQ(grid.source_id, serial.source_id) << threads << " threads, " << bands << " bands";
      for (size_t i = 0; i < grid.num_cells(); ++i) {
        ASSERT_TRUE(grid.top_z[i] == serial.top_z[i] || (std::isnan(grid.top_z[i]) && std::isnan(serial.top_z[i])))
            << "cell " << i;
      }
    }
  }
  EXPECT_GT(serial.count[serial.Index(0, 0)], 0u);
}

}  // namespace
}  // namespace sacfuse
