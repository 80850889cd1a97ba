#include "io/colour_raster_io.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

RgbImage Gradient(int w, int h, int channels) {
  RgbImage image(w, h, channels);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      for (int ch = 0; ch < channels; ++ch) image.at(r, c, ch) = static_cast<uint8_t>(r * 17 + c * 5 + ch * 101);
  return image;
}

TEST(ColourRasterIoTest, WindowsEqualTheCropOfTheWrittenRaster) {
  testing::TempDir dir;
  for (const int channels : {1, 3}) {
    const std::string path = (dir / "sub" / ("v" + std::to_string(channels) + ".rgb")).string();
    const RgbImage image = Gradient(23, 11, channels);
    WriteColourRaster(path, image);
    const ColourRasterInfo info = ReadColourRasterInfo(path);
    EXPECT_EQ(info.width, 23);
    EXPECT_EQ(info.height, 11);
    EXPECT_EQ(info.channels, channels);
    EXPECT_EQ(std::filesystem::file_size(path), 24u + 23u * 11u * channels);
    for (const PixelWindow& w : {PixelWindow{0, 11, 0, 23}, PixelWindow{3, 4, 7, 20}, PixelWindow{10, 11, 22, 23}}) {
      const RgbImage win = ReadColourRasterWindow(path, w);
      ASSERT_EQ(win.width, w.width());
      ASSERT_EQ(win.height, w.height());
      for (int r = 0; r < w.height(); ++r)
        for (int c = 0; c < w.width(); ++c)
          for (int ch = 0; ch < channels; ++ch)
            ASSERT_EQ(win.at(r, c, ch), image.at(w.row_begin + r, w.col_begin + c, ch));
    }
    EXPECT_THROW(ReadColourRasterWindow(path, PixelWindow{0, 12, 0, 5}), Error);
  }
}

TEST(ColourRasterIoTest, TruncatedOrForeignFilesAreRejectedNamingTheFile) {
  testing::TempDir dir;
  const std::string path = (dir / "v.rgb").string();
  WriteColourRaster(path, Gradient(8, 8, 3));
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 1);
  try {
    ReadColourRasterWindow(path, PixelWindow{0, 1, 0, 1});
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << "NOTRGB01 and some more bytes here";
  EXPECT_THROW(ReadColourRasterInfo(path), InputError);
  EXPECT_THROW(ReadColourRasterInfo((dir / "missing.rgb").string()), InputError);
  EXPECT_THROW(WriteColourRaster(path, RgbImage()), Error);
}

}  // namespace
}  // namespace sacfuse
