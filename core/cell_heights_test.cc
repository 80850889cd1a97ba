// The cells of raster products (CellWindow) and the per-cell height rule (CellHeights), on hand-made points with
// known answers.
#include "core/cell_heights.h"

#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "core/cell_window.h"

namespace sacfuse {
namespace {

TEST(CellWindowTest, CellsAreHalfOpenMultiplesOfTheCellAndRasterRowsRunSouth) {
  EXPECT_EQ(CellIndexOf(0.0, 0.5), 0);
  EXPECT_EQ(CellIndexOf(0.4999, 0.5), 0);
  EXPECT_EQ(CellIndexOf(0.5, 0.5), 1);
  EXPECT_EQ(CellIndexOf(-0.0001, 0.5), -1);
  EXPECT_EQ(CellIndexOf(770500.3, 0.1), 7705003);  // 0.1 is not exact in binary: the edge formula decides
  EXPECT_LE(CellEdge(7705003, 0.1), 770500.3);
  // Any coordinate, either sign, on lattices that are and are not exact in binary: the cell whose edges hold it.
  uint64_t state = 12345;
  for (const double cell : {0.1, 0.25, 0.3, 1.0, 7.3}) {
    for (int i = 0; i < 20000; ++i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      const double v = (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 2e6 * (i % 2 ? 1.0 : 1e-5);
      const int64_t k = CellIndexOf(v, cell);
      ASSERT_LE(CellEdge(k, cell), v) << v << " in cells of " << cell;
      ASSERT_GT(CellEdge(k + 1, cell), v) << v << " in cells of " << cell;
    }
    EXPECT_EQ(CellIndexOf(CellEdge(-7, cell), cell), -7);  // an edge belongs to the cell it starts
  }
  // A tile core [20, 40) x [0, 20) with 0.5 m cells: exactly 40 x 40 cells from column 40, row 0.
  const CellWindow core = CellWindowOfHalfOpen(Box2d(20, 0, 40, 20), 0.5);
  EXPECT_EQ(core.col0, 40);
  EXPECT_EQ(core.row0, 0);
  EXPECT_EQ(core.cols, 40);
  EXPECT_EQ(core.rows, 40);
  // A closed area covers the cell its max edge falls in.
  const CellWindow area = CellWindowCovering(Box2d(20, 0, 40, 20), 0.5);
  EXPECT_EQ(area.cols, 41);
  EXPECT_DOUBLE_EQ(area.north(), 20.5);
  // North-up: the northern row is raster row 0.
  EXPECT_EQ(core.Index(40, 39), 0u);
  EXPECT_EQ(core.Index(41, 39), 1u);
  EXPECT_EQ(core.Index(40, 38), 40u);
  EXPECT_EQ(core.YOffsetIn(core.Grown(3)), 3);
  EXPECT_TRUE(IsWholeNumberOfCells(25.0, 0.2));
  EXPECT_TRUE(IsWholeNumberOfCells(20.0, 0.1));
  EXPECT_FALSE(IsWholeNumberOfCells(25.0, 2.0));
}

TEST(CellWindowTest, BlocksAreAlignedToTheLatticeAndCoverTheExtentOnce) {
  CellWindow extent;
  extent.cell_m = 1.0;
  extent.col0 = -5;
  extent.row0 = 3;
  extent.cols = 23;
  extent.rows = 9;
  const std::vector<CellBlock> blocks = CellBlocksOf(extent, 10);
  ASSERT_EQ(blocks.size(), 3u * 2u);  // columns [-10,0) [0,10) [10,20) [20,30) clipped to [-5,18): 3; rows 2
  size_t cells = 0;
  for (const CellBlock& b : blocks) {
    cells += b.window.size();
    EXPECT_EQ(b.window.Intersection(extent), b.window);
    EXPECT_EQ(((b.window.col0 % 10) + 10) % 10 == 0 || b.window.col0 == extent.col0, true);
  }
  EXPECT_EQ(cells, extent.size());
  EXPECT_GT(blocks.front().by, blocks.back().by);  // north first
}

TEST(CellHeightsTest, QuantileOfEachCellsHeightsAsScoreDsmGridsThem) {
  CellWindow w;
  w.cell_m = 1.0;
  w.cols = 2;
  w.rows = 1;
  CellHeights h(w);
  // Cell (0, 0): heights 1..10; cell (1, 0): one point.
  for (int k = 1; k <= 10; ++k) h.Add(0.5, 0.5, k);
  h.Add(1.2, 0.9, 7.25);
  h.Add(2.5, 0.5, 99);  // outside
  EXPECT_EQ(h.points(), 11u);
  EXPECT_EQ(h.ignored(), 1u);
  CellHeights copy = h;
  // q = 0.9 over 10 values: index floor(0.9 * 9 + 0.5) = 8 -> the 9th value.
  const std::vector<float> p90 = h.Reduce(0.9, 1);
  EXPECT_FLOAT_EQ(p90[0], 9.0f);
  EXPECT_FLOAT_EQ(p90[1], 7.25f);
  const std::vector<float> median = copy.Reduce(0.5, 2);  // index floor(4.5 + 0.5) = 5 -> 6
  EXPECT_FLOAT_EQ(median[0], 6.0f);
  EXPECT_TRUE(std::isnan(median[1]));  // one point < min_points
}

TEST(CellHeightsTest, NegativeHeightsSortBelowPositiveOnes) {
  CellWindow w;
  w.cell_m = 1.0;
  w.cols = w.rows = 1;
  CellHeights h(w);
  for (const double z : {-3.5, 2.0, -0.25, 0.0, -10.0}) h.Add(0.5, 0.5, z);
  EXPECT_FLOAT_EQ(h.Reduce(0.0, 1)[0], -10.0f);
  CellHeights g(w);
  for (const double z : {-3.5, 2.0, -0.25, 0.0, -10.0}) g.Add(0.5, 0.5, z);
  EXPECT_FLOAT_EQ(g.Reduce(1.0, 1)[0], 2.0f);
}

TEST(CellHeightsTest, OneCellsValueFromItsHeightsIsTheReducedValue) {
  CellWindow w;
  w.cell_m = 1.0;
  w.cols = w.rows = 1;
  const std::vector<double> zs = {4.0, -0.0, 0.0, -2.5, 7.125, 3.0, 3.0, 1e-3};
  for (const double q : {0.0, 0.3, 0.5, 0.9, 1.0}) {
    CellHeights h(w);
    std::vector<float> z;
    for (const double v : zs) {
      h.Add(0.5, 0.5, v);
      z.push_back(static_cast<float>(v));
    }
    const float reduced = h.Reduce(q, 1)[0];
    const float one = CellValueOf(&z, q, 1);
    EXPECT_EQ(std::memcmp(&reduced, &one, sizeof(float)), 0) << "q " << q << ": " << reduced << " vs " << one;
  }
  std::vector<float> two = {1.0f, 2.0f};
  EXPECT_TRUE(std::isnan(CellValueOf(&two, 0.5, 3)));
  std::vector<float> none;
  EXPECT_TRUE(std::isnan(CellValueOf(&none, 0.5, 1)));
}

// Reduce scans the sorted points in ranges on the job's threads: every cell, also one whose points straddle two
// ranges (a cell of 200,000 points is longer than a range), gets the value its own heights give, on any thread
// count.
TEST(CellHeightsTest, ReducedValuesAreEachCellsOwnOnAnyThreadCount) {
  CellWindow w;
  w.cell_m = 1.0;
  w.cols = 40;
  w.rows = 30;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> xy(0.0, 40.0), z(-5.0, 50.0);
  std::vector<std::vector<float>> per_cell(w.size());
  std::vector<std::array<double, 3>> points;
  for (int i = 0; i < 300000; ++i) {
    // Most points in one cell (long runs of equal cells), the rest scattered; some cells stay empty.
    const double x = i % 3 == 0 ? 7.5 : xy(rng), y = i % 3 == 0 ? 4.5 : std::fmod(xy(rng), 30.0);
    if (x > 30.0 && y > 20.0) continue;
    points.push_back({x, y, z(rng)});
    per_cell[w.Index(CellIndexOf(x, 1.0), CellIndexOf(y, 1.0))].push_back(static_cast<float>(points.back()[2]));
  }
  std::vector<float> expected(w.size());
  for (size_t c = 0; c < w.size(); ++c) expected[c] = CellValueOf(&per_cell[c], 0.5, 2);
  for (const int threads : {1, 2, 4}) {
    std::vector<float> got;
    tbb::task_arena(threads).execute([&] {
      CellHeights h(w);
      for (const auto& p : points) h.Add(p[0], p[1], p[2]);
      got = h.Reduce(0.5, 2);
    });
    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(std::memcmp(got.data(), expected.data(), got.size() * sizeof(float)), 0) << threads << " threads";
  }
}

}  // namespace
}  // namespace sacfuse
