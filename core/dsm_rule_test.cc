// The DSM's finishing steps (core/dsm_rule.h) on hand-made rasters with known answers, and the property that makes
// tiles and blocks seam-free: finishing a block from its cells plus the halo equals finishing the whole raster.
#include "core/dsm_rule.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/cell_heights.h"
#include "core/error.h"

namespace sacfuse {
namespace {

constexpr float kNone = kNoCellValue;

CellWindow Window(int64_t col0, int64_t row0, int64_t cols, int64_t rows) {
  CellWindow w;
  w.cell_m = 0.5;
  w.col0 = col0;
  w.row0 = row0;
  w.cols = cols;
  w.rows = rows;
  return w;
}

// Finishes the whole raster `w` (cells outside it have no value).
std::vector<float> FinishWhole(const std::vector<float>& raw, const CellWindow& w, const DsmRule& rule,
                               DsmFinishStats* stats = nullptr) {
  const CellWindow outer = w.Grown(DsmHaloCells(rule, w.cell_m));
  std::vector<float> padded(outer.size(), kNone);
  for (int64_t row = w.row0; row < w.row0 + w.rows; ++row) {
    for (int64_t col = w.col0; col < w.col0 + w.cols; ++col) padded[outer.Index(col, row)] = raw[w.Index(col, row)];
  }
  return FinishDsm(padded, outer, w, rule, stats);
}

TEST(DsmRuleTest, SmallHolesAreFilledFromTheirRimLargeAndOpenOnesStay) {
  const CellWindow w = Window(0, 0, 20, 12);
  std::vector<float> raw(w.size(), 10.0f);
  // A 2 x 1 hole inside a flat 10 m surface: filled with 10.
  raw[w.Index(5, 5)] = raw[w.Index(6, 5)] = kNone;
  // A 6 x 6 hole: larger than max_hole_m = 2 m = 4 cells: stays.
  for (int64_t r = 2; r < 8; ++r) {
    for (int64_t c = 11; c < 17; ++c) raw[w.Index(c, r)] = kNone;
  }
  // A hole touching the raster's edge: open, stays.
  raw[w.Index(0, 10)] = kNone;
  DsmRule rule;
  rule.max_hole_m = 2.0;
  DsmFinishStats stats;
  const std::vector<float> out = FinishWhole(raw, w, rule, &stats);
  EXPECT_FLOAT_EQ(out[w.Index(5, 5)], 10.0f);
  EXPECT_FLOAT_EQ(out[w.Index(6, 5)], 10.0f);
  EXPECT_TRUE(std::isnan(out[w.Index(13, 4)]));
  EXPECT_TRUE(std::isnan(out[w.Index(0, 10)]));
  EXPECT_EQ(stats.cells_filled, 2u);
}

TEST(DsmRuleTest, FilledCellsAreInverseDistanceWeightedRimValues) {
  // One missing cell on the western edge of a 4 m step (columns 0-2 at 0 m, 3-6 at 4 m); its rim: the column west
  // of it (0 m), the cells north and south of it and the column east of it (4 m).
  const CellWindow w = Window(0, 0, 7, 7);
  std::vector<float> raw(w.size(), 0.0f);
  for (int64_t r = 0; r < 7; ++r) {
    for (int64_t c = 3; c < 7; ++c) raw[w.Index(c, r)] = 4.0f;
  }
  raw[w.Index(3, 3)] = kNone;
  DsmRule rule;
  rule.max_hole_m = 1.0;
  const std::vector<float> out = FinishWhole(raw, w, rule);
  // Weights 1/d^2: west column (3 cells: d^2 = 1, 2, 2) at 0 m; north, south (d^2 = 1) and east column (1, 2, 2)
  // at 4 m. Value = 4 * (1 + 1 + 1 + 0.5 + 0.5) / (2 * (1 + 0.5 + 0.5) + 2) = 4 * 4 / 6.
  EXPECT_NEAR(out[w.Index(3, 3)], 4.0 * 4.0 / 6.0, 1e-5);
}

TEST(DsmRuleTest, BlocksFinishedWithTheHaloEqualTheWholeRasterBitForBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> height(0.0f, 30.0f);
  std::bernoulli_distribution missing(0.25);
  const CellWindow w = Window(-13, 7, 71, 53);
  std::vector<float> raw(w.size());
  for (float& v : raw) v = missing(rng) ? kNone : height(rng);
  // Some larger holes, some crossing block borders.
  for (int64_t r = 20; r < 27; ++r) {
    for (int64_t c = 10; c < 13; ++c) raw[w.Index(c, r)] = kNone;
  }
  DsmRule rule;
  rule.max_hole_m = 2.5;
  const std::vector<float> whole = FinishWhole(raw, w, rule);
  const int64_t halo = DsmHaloCells(rule, w.cell_m);
  for (const int64_t block : {8, 17, 32}) {
    for (const CellBlock& b : CellBlocksOf(w, block)) {
      const CellWindow outer = b.window.Grown(halo);
      std::vector<float> part(outer.size(), kNone);
      for (int64_t row = outer.row0; row < outer.row0 + outer.rows; ++row) {
        for (int64_t col = outer.col0; col < outer.col0 + outer.cols; ++col) {
          if (w.Contains(col, row)) part[outer.Index(col, row)] = raw[w.Index(col, row)];
        }
      }
      const std::vector<float> finished = FinishDsm(part, outer, b.window, rule);
      for (int64_t row = b.window.row0; row < b.window.row0 + b.window.rows; ++row) {
        for (int64_t col = b.window.col0; col < b.window.col0 + b.window.cols; ++col) {
          const float a = finished[b.window.Index(col, row)], e = whole[w.Index(col, row)];
          ASSERT_TRUE((std::isnan(a) && std::isnan(e)) || a == e)
              << "block " << block << " cell " << col << "," << row << ": " << a << " vs " << e;
        }
      }
    }
  }
}

TEST(DsmRuleTest, TooSmallAHaloIsRefused) {
  const CellWindow w = Window(0, 0, 4, 4);
  DsmRule rule;
  rule.max_hole_m = 2.0;
  EXPECT_THROW(FinishDsm(std::vector<float>(w.size(), 1.0f), w, w, rule), Error);
}

}  // namespace
}  // namespace sacfuse
