#include "core/superpixel_labels.h"

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

TEST(SuperpixelLabelsTest, BandedStorageGivesBackEveryLabelAtTwoBytesPerPixel) {
  // 150 rows: three bands (64, 64, 22 rows); the last band's base is 128 * 500 = 64,000, beyond a u16.
  const std::vector<int32_t> labels = BandLikeLabels(37, 150, 500);
  const SuperpixelLabels stored(37, 150, labels);
  ASSERT_TRUE(stored.banded());
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
