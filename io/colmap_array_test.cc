#include "io/colmap_array.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using sacfuse::testing::TempDir;

std::string FloatBytes(const std::vector<float>& values) {
  std::string bytes;
  for (const float v : values) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    for (int i = 0; i < 4; ++i) bytes += static_cast<char>((bits >> (8 * i)) & 0xff);  // little-endian
  }
  return bytes;
}

std::string WriteBytes(const TempDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void ExpectArrayError(const std::string& path, const std::vector<std::string>& parts) {
  try {
    ReadColmapArray(path);
    FAIL() << "expected an InputError for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    for (const std::string& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(ColmapArrayTest, HandBuiltSingleChannel) {
  TempDir tmp;
  const std::string path = WriteBytes(tmp, "d.bin", "3&2&1&" + FloatBytes({0.5f, 1.5f, 2.5f, 10.0f, -1.0f, 1e-3f}));
  const ColmapArrayShape shape = ReadColmapArrayShape(path);
  EXPECT_EQ(shape.width, 3);
  EXPECT_EQ(shape.height, 2);
  EXPECT_EQ(shape.channels, 1);
  EXPECT_EQ(shape.data_offset, 6u);
  const Raster<float> r = ReadColmapArray(path);
  ASSERT_EQ(r.width, 3);
  ASSERT_EQ(r.height, 2);
  ASSERT_EQ(r.channels, 1);
  EXPECT_EQ(r.at(0, 0), 0.5f);
  EXPECT_EQ(r.at(0, 2), 2.5f);
  EXPECT_EQ(r.at(1, 0), 10.0f);
  EXPECT_EQ(r.at(1, 1), -1.0f);
  EXPECT_EQ(r.at(1, 2), 1e-3f);
}

TEST(ColmapArrayTest, ThreeChannelPlanarBecomesInterleaved) {
  TempDir tmp;
  // 2 wide, 2 high, 3 channels; value = 100*c + 10*row + col, stored channel-planar.
  std::vector<float> planar;
  for (int c = 0; c < 3; ++c) {
    for (int row = 0; row < 2; ++row) {
      for (int col = 0; col < 2; ++col) planar.push_back(100.0f * c + 10.0f * row + col);
    }
  }
  const std::string path = WriteBytes(tmp, "n.bin", "2&2&3&" + FloatBytes(planar));
  const Raster<float> r = ReadColmapArray(path);
  ASSERT_EQ(r.channels, 3);
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 2; ++col) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(r.at(row, col, c), 100.0f * c + 10.0f * row + col);
    }
  }
  // Interleaved in memory: pixel (0,1) holds its three channels next to each other.
  EXPECT_EQ(r.data[3], 1.0f);
  EXPECT_EQ(r.data[4], 101.0f);
  EXPECT_EQ(r.data[5], 201.0f);
}

TEST(ColmapArrayTest, WriteProducesColmapBytes) {
  TempDir tmp;
  Raster<float> r(2, 1, 2);
  r.at(0, 0, 0) = 1.0f;
  r.at(0, 1, 0) = 2.0f;
  r.at(0, 0, 1) = 3.0f;
  r.at(0, 1, 1) = 4.0f;
  const std::string path = (tmp / "sub/dir/x.bin").string();
  WriteColmapArray(path, r);
  EXPECT_EQ(ReadBytes(path), "2&1&2&" + FloatBytes({1.0f, 2.0f, 3.0f, 4.0f}));
  // No temporary file left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(tmp / "sub/dir"), {}), 1);
}

Raster<float> RandomRaster(int w, int h, int c) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> dist(-100.0f, 100.0f);
  Raster<float> r(w, h, c);
  for (float& v : r.data) v = dist(rng);
  return r;
}

// Every value of `got` equals expected(row, col, channel); stops at the first difference.
template <typename Expected>
void ExpectValues(const Raster<float>& got, Expected expected) {
  for (int row = 0; row < got.height; ++row) {
    for (int col = 0; col < got.width; ++col) {
      for (int c = 0; c < got.channels; ++c) {
        if (got.at(row, col, c) == expected(row, col, c)) continue;
        ADD_FAILURE() << "at row " << row << ", col " << col << ", channel " << c << ": " << got.at(row, col, c)
                      << " != " << expected(row, col, c);
        return;
      }
    }
  }
}

TEST(ColmapArrayTest, RoundTripAndRowsEqualSliceOfFullRead) {
  TempDir tmp;
  for (const int channels : {1, 3}) {
    const Raster<float> written = RandomRaster(9, 7, channels);
    const std::string path = (tmp / ("a" + std::to_string(channels) + ".bin")).string();
    WriteColmapArray(path, written);
    const Raster<float> full = ReadColmapArray(path);
    EXPECT_EQ(full.data, written.data);
    for (const auto& [begin, end] : std::vector<std::pair<int, int>>{{0, 7}, {2, 5}, {6, 7}, {0, 1}, {3, 3}}) {
      const Raster<float> rows = ReadColmapArrayRows(path, begin, end);
      ASSERT_EQ(rows.width, 9);
      ASSERT_EQ(rows.height, end - begin);
      ASSERT_EQ(rows.channels, channels);
      ExpectValues(rows, [&](int row, int col, int c) { return full.at(begin + row, col, c); });
    }
    EXPECT_THROW(ReadColmapArrayRows(path, 5, 8), InputError);
    EXPECT_THROW(ReadColmapArrayRows(path, -1, 2), InputError);
    EXPECT_THROW(ReadColmapArrayRows(path, 4, 3), InputError);
  }
}

TEST(ColmapArrayTest, WindowsEqualTheCropOfTheFullRead) {
  TempDir tmp;
  for (const int channels : {1, 3}) {
    const Raster<float> written = RandomRaster(9, 7, channels);
    const std::string path = (tmp / ("w" + std::to_string(channels) + ".bin")).string();
    WriteColmapArray(path, written);
    for (const PixelWindow& w : {PixelWindow{0, 7, 0, 9}, PixelWindow{2, 5, 3, 4}, PixelWindow{6, 7, 8, 9},
                                 PixelWindow{1, 6, 0, 5}}) {
      SCOPED_TRACE(PixelWindowText(w));
      const Raster<float> win = ReadColmapArrayWindow(path, w);
      ASSERT_EQ(win.width, w.width());
      ASSERT_EQ(win.height, w.height());
      ASSERT_EQ(win.channels, channels);
      ExpectValues(win, [&](int r, int col, int c) { return written.at(w.row_begin + r, w.col_begin + col, c); });
    }
    EXPECT_THROW(ReadColmapArrayWindow(path, PixelWindow{0, 8, 0, 9}), Error);
    EXPECT_THROW(ReadColmapArrayWindow(path, PixelWindow{0, 7, 5, 10}), Error);
    EXPECT_THROW(ReadColmapArrayWindow(path, PixelWindow{3, 3, 0, 9}), Error);
  }
}

TEST(ColmapArrayTest, RowListsEqualTheRowsOfTheFullRead) {
  TempDir tmp;
  for (const int channels : {1, 3}) {
    const Raster<float> written = RandomRaster(9, 7, channels);
    const std::string path = (tmp / ("l" + std::to_string(channels) + ".bin")).string();
    WriteColmapArray(path, written);
    for (const std::vector<int>& rows : {std::vector<int>{1, 4}, std::vector<int>{6, 0, 6}, std::vector<int>{}}) {
      const Raster<float> got = ReadColmapArrayRowList(path, rows);
      ASSERT_EQ(got.width, 9);
      ASSERT_EQ(got.height, static_cast<int>(rows.size()));
      ASSERT_EQ(got.channels, channels);
      ExpectValues(got, [&](int i, int col, int c) { return written.at(rows[i], col, c); });
    }
    EXPECT_THROW(ReadColmapArrayRowList(path, {0, 7}), Error);
    EXPECT_THROW(ReadColmapArrayRowList(path, {-1}), Error);
  }
}

TEST(ColmapArrayTest, TruncatedFile) {
  TempDir tmp;
  const std::string path = WriteBytes(tmp, "t.bin", "3&2&1&" + FloatBytes({1, 2, 3, 4, 5}).substr(0, 18));
  ExpectArrayError(path, {"truncated", "3x2x1", "30 bytes", "24 bytes"});
  ExpectArrayError(WriteBytes(tmp, "h.bin", "3&2&"), {"truncated"});
  ExpectArrayError(WriteBytes(tmp, "e.bin", ""), {"truncated"});
  EXPECT_THROW(ReadColmapArrayRows(path, 0, 1), InputError);
}

TEST(ColmapArrayTest, TooLargeFileIsMismatched) {
  TempDir tmp;
  const std::string path = WriteBytes(tmp, "m.bin", "1&1&1&" + FloatBytes({1, 2}));
  ExpectArrayError(path, {"mismatched", "10 bytes", "14 bytes"});
}

TEST(ColmapArrayTest, GarbageHeader) {
  TempDir tmp;
  ExpectArrayError(WriteBytes(tmp, "g1.bin", "hello world, this is not a depth map at all" + std::string(40, 'x')),
                   {"garbage"});
  ExpectArrayError(WriteBytes(tmp, "g2.bin", "3,2,1," + FloatBytes({1, 2, 3, 4, 5, 6})), {"garbage"});
  ExpectArrayError(WriteBytes(tmp, "g3.bin", " 3&2&1&" + FloatBytes({1, 2, 3, 4, 5, 6})), {"garbage"});
  ExpectArrayError(WriteBytes(tmp, "g4.bin", "-3&2&1&" + FloatBytes({1, 2, 3, 4, 5, 6})), {"garbage"});
  ExpectArrayError(WriteBytes(tmp, "g5.bin", "3&&1&" + FloatBytes({1, 2, 3, 4, 5, 6})), {"garbage"});
  ExpectArrayError(WriteBytes(tmp, "g6.bin", "99999999999&2&1&" + FloatBytes({1, 2, 3, 4, 5, 6})), {"garbage"});
}

TEST(ColmapArrayTest, HeaderWithFourFields) {
  TempDir tmp;
  ExpectArrayError(WriteBytes(tmp, "f.bin", "3&2&1&1&" + FloatBytes({1, 2, 3, 4, 5, 6})), {"more than 3 fields"});
}

TEST(ColmapArrayTest, ZeroSizes) {
  TempDir tmp;
  ExpectArrayError(WriteBytes(tmp, "w.bin", "0&2&1&"), {"width 0"});
  ExpectArrayError(WriteBytes(tmp, "h.bin", "2&0&1&"), {"height 0"});
  ExpectArrayError(WriteBytes(tmp, "c.bin", "2&2&0&"), {"channels 0"});
  EXPECT_THROW(WriteColmapArray((tmp / "empty.bin").string(), Raster<float>()), Error);
}

TEST(ColmapArrayTest, MissingFile) {
  TempDir tmp;
  ExpectArrayError((tmp / "nope.bin").string(), {"does not exist"});
}

}  // namespace
}  // namespace sacfuse
