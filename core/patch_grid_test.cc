#include "core/patch_grid.h"

#include <vector>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

// 5 x 7 pixels in patches of 2 x 3: 3 bands of 3 patches, clipped at the bottom and right edges.
TEST(PatchGridTest, PatchesTileTheRasterBandByBand) {
  const PatchGrid grid(5, 7, 2, 3);
  EXPECT_EQ(grid.bands(), 3);
  EXPECT_EQ(grid.patches_per_band(), 3);
  ASSERT_EQ(grid.size(), 9);
  EXPECT_EQ(grid.Patch(0), (PixelWindow{0, 2, 0, 3}));
  EXPECT_EQ(grid.Patch(2), (PixelWindow{0, 2, 6, 7}));
  EXPECT_EQ(grid.Patch(4), (PixelWindow{2, 4, 3, 6}));
  EXPECT_EQ(grid.Patch(8), (PixelWindow{4, 5, 6, 7}));
  EXPECT_EQ(grid.BandRowBegin(2), 4);
  EXPECT_EQ(grid.BandRowEnd(2), 5);
  // Every pixel lies in exactly one patch.
  std::vector<int> hits(5 * 7, 0);
  for (int i = 0; i < grid.size(); ++i) {
    const PixelWindow w = grid.Patch(i);
    for (int r = w.row_begin; r < w.row_end; ++r) {
      for (int c = w.col_begin; c < w.col_end; ++c) ++hits[r * 7 + c];
    }
  }
  for (const int h : hits) EXPECT_EQ(h, 1);
}

}  // namespace
}  // namespace sacfuse
