#include "core/superpixel_labels.h"

#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

// Labels numbered like our SLIC's: growing down the raster, each band of 64 rows within a small span.
std::vector<int32_t> BandLikeLabels(int width, int height, int32_t per_row) {
  std::vector<int32_t> labels(static_cast<size_t>(width) * height);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) labels[static_cast<size_t>(r) * width + c] = r * per_row + c % per_row;
  }
  return labels;
}

TEST(SuperpixelLabelsTest, BandedStorageWhereBlocksMeetTooManyLabels) {
  // 150 rows: three bands (64, 64, 22 rows); the last band's base is 128 * 500 = 64,000, beyond a u16.
  const std::vector<int32_t> labels = BandLikeLabels(37, 150, 500);
  const SuperpixelLabels stored(37, 150, labels);
  ASSERT_TRUE(stored.banded());
  EXPECT_FALSE(stored.paletted());  // a 16 x 16 block meets 256 labels here
  EXPECT_EQ(stored.band_base(), (std::vector<uint32_t>{0, 64 * 500, 128 * 500}));
  EXPECT_EQ(stored.bytes(), 37u * 150u * 2u + 3u * 4u);
  for (int r = 0; r < 150; ++r) {
    for (int c = 0; c < 37; ++c) ASSERT_EQ(stored.at(r, c), labels[static_cast<size_t>(r) * 37 + c]) << r << "," << c;
  }
  EXPECT_EQ(stored.ToVector(), labels);
  std::vector<int32_t> row(37);
  stored.CopyRow(149, row.data());
  EXPECT_EQ(row[36], 149 * 500 + 36);
  EXPECT_EQ(stored, SuperpixelLabels(37, 150, labels));
}

// Superpixel-like labels: cells of 12 x 20 pixels with wavy borders, numbered row by row, on a raster whose size is
// not a multiple of the 16-pixel blocks.
std::vector<int32_t> CellLabels(int width, int height) {
  std::vector<int32_t> labels(static_cast<size_t>(width) * height);
  const int cells_per_row = width / 20 + 2;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const int cr = (r + (c % 7 == 0 ? 3 : 0)) / 12, cc = (c + (r % 5 == 0 ? 4 : 0)) / 20;
      labels[static_cast<size_t>(r) * width + c] = cr * cells_per_row + cc;
    }
  }
  return labels;
}

TEST(SuperpixelLabelsTest, PaletteStorageGivesBackEveryLabelAtAboutHalfAByteAPixel) {
  const int width = 203, height = 157;  // odd: the last pixel has a byte of its own
  const std::vector<int32_t> labels = CellLabels(width, height);
  const SuperpixelLabels stored(width, height, labels);
  ASSERT_TRUE(stored.paletted());
  ASSERT_TRUE(stored.banded());  // the cache file's layout is still known
  EXPECT_EQ(stored.band_base(), (std::vector<uint32_t>{0, static_cast<uint32_t>(labels[64 * width]),
                                                       static_cast<uint32_t>(labels[128 * width])}));
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      ASSERT_EQ(stored.at(r, c), labels[static_cast<size_t>(r) * width + c]) << r << "," << c;
    }
  }
  EXPECT_EQ(stored.ToVector(), labels);
  EXPECT_LT(stored.bytes(), stored.size() * 7 / 10);
  EXPECT_EQ(stored, SuperpixelLabels(width, height, labels));
  std::vector<int32_t> other = labels;
  other[static_cast<size_t>(100) * width + 7] += 1;
  EXPECT_NE(stored, SuperpixelLabels(width, height, other));

  // A block meeting exactly 16 labels keeps its palette; 17 do not (u16 offsets instead).
  std::vector<int32_t> sixteen(16 * 16);
  for (size_t i = 0; i < sixteen.size(); ++i) sixteen[i] = static_cast<int32_t>(i % 16);
  EXPECT_TRUE(SuperpixelLabels(16, 16, sixteen).paletted());
  sixteen[255] = 16;
  const SuperpixelLabels seventeen(16, 16, sixteen);
  EXPECT_FALSE(seventeen.paletted());
  EXPECT_TRUE(seventeen.banded());
  EXPECT_EQ(seventeen.ToVector(), sixteen);
}

TEST(SuperpixelLabelsTest, ABandSpanningMoreThanAU16OrNegativeLabelsKeepInt32) {
  // Row 0: 0..9; row 1: 70,000..70,009: one band spans 70,009 labels.
  std::vector<int32_t> labels(20);
  for (int c = 0; c < 10; ++c) {
    labels[static_cast<size_t>(c)] = c;
    labels[static_cast<size_t>(10 + c)] = 70000 + c;
  }
  const SuperpixelLabels wide(10, 2, labels);
  EXPECT_FALSE(wide.banded());
  EXPECT_EQ(wide.at(1, 9), 70009);
  EXPECT_EQ(wide.ToVector(), labels);
  EXPECT_EQ(wide.bytes(), 20u * 4u);

  labels = BandLikeLabels(5, 3, 5);
  labels[7] = -1;
  const SuperpixelLabels negative(5, 3, labels);
  EXPECT_FALSE(negative.banded());
  EXPECT_EQ(negative.at(1, 2), -1);

  // Exactly 65,535 apart still fits.
  EXPECT_TRUE(SuperpixelLabels(2, 1, {7, 7 + 65535}).banded());
  EXPECT_FALSE(SuperpixelLabels(2, 1, {7, 7 + 65536}).banded());
}

TEST(SuperpixelLabelsTest, UnpackedLabelsHoldTheSameLabelsAndBands) {
  // Three layouts the packed labels would pick: palettes, banded u16 offsets, int32 (a band beyond a u16).
  const std::vector<std::pair<int, int>> sizes = {{203, 157}, {37, 150}, {2, 1}};
  const std::vector<std::vector<int32_t>> cases = {CellLabels(203, 157), BandLikeLabels(37, 150, 500), {7, 7 + 65536}};
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(i);
    const auto [width, height] = sizes[i];
    const SuperpixelLabels packed(width, height, cases[i]);
    const SuperpixelLabels unpacked = SuperpixelLabels::Unpacked(width, height, cases[i]);
    EXPECT_FALSE(unpacked.paletted());
    EXPECT_EQ(unpacked.bytes(), cases[i].size() * 4 + unpacked.band_base().size() * 4);
    EXPECT_EQ(unpacked.banded(), packed.banded());
    EXPECT_EQ(unpacked.band_base(), packed.band_base());
    EXPECT_EQ(unpacked.ToVector(), cases[i]);
    EXPECT_EQ(unpacked.at(height - 1, width - 1), cases[i].back());
  }
  EXPECT_THROW(SuperpixelLabels::Unpacked(3, 2, std::vector<int32_t>(5, 0)), Error);
}

TEST(SuperpixelLabelsTest, SizeMismatchThrowsAndEmptyIsFine) {
  EXPECT_THROW(SuperpixelLabels(3, 2, std::vector<int32_t>(5, 0)), Error);
  EXPECT_THROW(SuperpixelLabels(-1, 0, {}), Error);
  const SuperpixelLabels empty(0, 0, {});
  EXPECT_TRUE(empty.empty());
  EXPECT_TRUE(empty.ToVector().empty());
  EXPECT_EQ(empty, SuperpixelLabels());
}

}  // namespace
}  // namespace sacfuse
