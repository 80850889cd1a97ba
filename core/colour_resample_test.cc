#include "core/colour_resample.h"

#include <cstdint>
#include <utility>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

// A 4 x 2 RGB image whose every byte says where it is: 100 * row + 10 * col + channel.
RgbImage CodedImage() {
  RgbImage image(4, 2, 3);
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < image.width; ++c) {
      for (int ch = 0; ch < 3; ++ch) image.at(r, c, ch) = static_cast<uint8_t>(100 * r + 10 * c + ch);
    }
  }
  return image;
}

TEST(ColourResampleTest, HalfSizeGridTakesThePixelUnderEachCentre) {
  // Depth pixel (0, c) has its centre at image column (c + 0.5) * 2 = 1 or 3, row 1.
  const RgbImage out = ResampleColourToDepthGrid(CodedImage(), 2, 1);
  ASSERT_EQ(out.width, 2);
  ASSERT_EQ(out.height, 1);
  EXPECT_EQ(out.at(0, 0, 0), 110);
  EXPECT_EQ(out.at(0, 1, 2), 132);
  EXPECT_EQ(ColoursOnDepthGrid(CodedImage(), 2, 1).data, out.data);
}

TEST(ColourResampleTest, AnImageOnTheDepthGridIsItsOwnResampling) {
  // The colour caches and the untiled runs take such an image as it is (ColoursOnDepthGrid): the same bytes, and
  // the same buffer, not a copy.
  const RgbImage image = CodedImage();
  const RgbImage out = ResampleColourToDepthGrid(image, 4, 2);
  EXPECT_EQ(out.channels, image.channels);
  EXPECT_EQ(out.data, image.data);
  RgbImage given = CodedImage();
  const uint8_t* buffer = given.data.data();
  const RgbImage taken = ColoursOnDepthGrid(std::move(given), 4, 2);
  EXPECT_EQ(taken.data, image.data);
  EXPECT_EQ(taken.data.data(), buffer);
  EXPECT_TRUE(ColoursOnDepthGrid(RgbImage(), 0, 0).empty());
}

}  // namespace
}  // namespace sacfuse
