#include "io/tiff_depth.h"

#include <gtest/gtest.h>
#include <tiffio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::TempDir;
using Compression = TiffDepthWriteOptions::Compression;

const float kNaN = std::numeric_limits<float>::quiet_NaN();

// A depth raster with valid values 50..150 m and invalid ones of every kind (0, negative, NaN, inf).
DepthMap TestDepth(int width, int height, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(50.0f, 150.0f);
  DepthMap d(width, height);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) d.at(r, c) = u(rng);
  }
  d.at(0, 0) = 0.0f;
  d.at(1, 2) = -5.0f;
  d.at(height - 1, width - 1) = kNaN;
  d.at(height / 2, width / 3) = std::numeric_limits<float>::infinity();
  return d;
}

// What a reader returns: invalid pixels as 0.
DepthMap Cleaned(DepthMap d) {
  for (float& v : d.data) v = IsValidDepth(v) ? v : 0.0f;
  return d;
}

DepthMap Crop(const DepthMap& d, const PixelWindow& w) {
  DepthMap out(w.width(), w.height());
  for (int r = 0; r < w.height(); ++r) {
    for (int c = 0; c < w.width(); ++c) out.at(r, c) = d.at(w.row_begin + r, w.col_begin + c);
  }
  return out;
}

void ExpectSame(const DepthMap& a, const DepthMap& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  for (size_t i = 0; i < a.data.size(); ++i) {
    ASSERT_EQ(a.data[i], b.data[i]) << "pixel " << i << " (row " << i / a.width << ", col " << i % a.width << ")";
  }
}

std::string ReadBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void WriteBytes(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

// Writes a TIFF with libtiff directly: `bits`-bit samples of `format`, `spp` bands, optional orientation.
void WriteOddTiff(const fs::path& path, uint16_t bits, uint16_t format, uint16_t spp, uint16_t orientation = 0) {
  TIFF* tif = TIFFOpen(path.c_str(), "w");
  ASSERT_NE(tif, nullptr);
  const uint32_t w = 8, h = 4;
  TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, w);
  TIFFSetField(tif, TIFFTAG_IMAGELENGTH, h);
  TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, bits);
  TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, spp);
  TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, format);
  TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, spp == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
  TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, h);
  if (orientation != 0) TIFFSetField(tif, TIFFTAG_ORIENTATION, orientation);
  std::vector<uint8_t> data(static_cast<size_t>(w) * h * spp * bits / 8, 0x40);
  ASSERT_GE(TIFFWriteEncodedStrip(tif, 0, data.data(), static_cast<tmsize_t>(data.size())), 0);
  TIFFClose(tif);
}

// Offsets and byte counts of every strip or tile of a TIFF (read with libtiff directly).
std::vector<std::pair<uint64_t, uint64_t>> DataBlocks(const fs::path& path) {
  TIFF* tif = TIFFOpen(path.c_str(), "r");
  EXPECT_NE(tif, nullptr);
  const bool tiled = TIFFIsTiled(tif);
  const uint32_t n = tiled ? TIFFNumberOfTiles(tif) : TIFFNumberOfStrips(tif);
  uint64_t* offsets = nullptr;
  uint64_t* counts = nullptr;
  TIFFGetField(tif, tiled ? TIFFTAG_TILEOFFSETS : TIFFTAG_STRIPOFFSETS, &offsets);
  TIFFGetField(tif, tiled ? TIFFTAG_TILEBYTECOUNTS : TIFFTAG_STRIPBYTECOUNTS, &counts);
  std::vector<std::pair<uint64_t, uint64_t>> out;
  for (uint32_t i = 0; i < n; ++i) out.emplace_back(offsets[i], counts[i]);
  TIFFClose(tif);
  return out;
}

// Runs `fn`, expecting an InputError whose message contains every part; also checks libtiff printed nothing.
template <typename Fn>
void ExpectInputError(Fn fn, const std::vector<std::string>& parts) {
  ::testing::internal::CaptureStderr();
  try {
    fn();
    ::testing::internal::GetCapturedStderr();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(err, "") << "libtiff printed to stderr";
    for (const std::string& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

TEST(TiffDepthTest, RoundTripsEveryLayoutAndCompression) {
  TempDir dir;
  const DepthMap depth = TestDepth(70, 45);
  int n = 0;
  for (const bool tiled : {true, false}) {
    for (const int block : {16, 32, 7, 100}) {
      if (tiled && block % 16 != 0) continue;
      for (const Compression comp : {Compression::kNone, Compression::kLzw, Compression::kDeflate}) {
        for (const std::optional<float> nodata :
             {std::optional<float>(), std::optional<float>(kNaN), std::optional<float>(-9999.0f)}) {
          TiffDepthWriteOptions o;
          o.tiled = tiled;
          o.tile_size_px = block;
          o.rows_per_strip = block;
          o.compression = comp;
          o.nodata = nodata;
          const fs::path path = dir / ("d" + std::to_string(n++) + ".tif");
          WriteTiffDepth(path.string(), depth, o);
          const TiffDepthInfo info = ReadTiffDepthInfo(path.string());
          EXPECT_EQ(info.width, 70);
          EXPECT_EQ(info.height, 45);
          EXPECT_EQ(info.tiled, tiled);
          if (tiled) {
            EXPECT_EQ(info.block_height, block);
          } else {  // libtiff may present a big uncompressed strip as smaller ones ("strip chopping")
            EXPECT_GE(info.block_height, 1);
            EXPECT_LE(info.block_height, std::min(block, 45));
          }
          EXPECT_EQ(info.nodata.has_value(), nodata.has_value());
          ExpectSame(ReadTiffDepth(path.string()), Cleaned(depth));
        }
      }
    }
  }
  for (const auto& e : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "temporary file left: " << e.path();
  }
}

TEST(TiffDepthTest, WindowsMatchTheWholeRaster) {
  TempDir dir;
  const DepthMap depth = TestDepth(100, 61, 5);
  const DepthMap clean = Cleaned(depth);
  for (const bool tiled : {true, false}) {
    TiffDepthWriteOptions o;
    o.tiled = tiled;
    o.tile_size_px = 32;
    o.rows_per_strip = 5;
    const fs::path path = dir / (tiled ? "t.tif" : "s.tif");
    WriteTiffDepth(path.string(), depth, o);
    TiffDepthReader reader(path.string());
    for (const PixelWindow& w : {PixelWindow{0, 61, 0, 100}, PixelWindow{0, 1, 0, 1}, PixelWindow{60, 61, 99, 100},
                                 PixelWindow{31, 33, 31, 33}, PixelWindow{10, 50, 40, 97}, PixelWindow{5, 6, 0, 100}}) {
      ExpectSame(ReadTiffDepthWindow(path.string(), w), Crop(clean, w));
      ExpectSame(reader.ReadWindow(w), Crop(clean, w));
    }
    EXPECT_THROW(ReadTiffDepthWindow(path.string(), PixelWindow{0, 62, 0, 10}), Error);
    EXPECT_THROW(ReadTiffDepthWindow(path.string(), PixelWindow{5, 5, 0, 10}), Error);
  }
}

// A window read decodes only the strips/tiles it intersects: with every other block's data destroyed, the window
// still reads exactly, while a whole read fails.
TEST(TiffDepthTest, WindowReadsTouchOnlyTheirStripsOrTiles) {
  TempDir dir;
  const DepthMap depth = TestDepth(64, 64, 9);
  for (const bool tiled : {true, false}) {
    TiffDepthWriteOptions o;
    o.tiled = tiled;
    o.tile_size_px = 16;
    o.rows_per_strip = 16;
    o.compression = Compression::kDeflate;
    const fs::path path = dir / (tiled ? "t.tif" : "s.tif");
    WriteTiffDepth(path.string(), depth, o);
    // The window: rows [20, 30) x cols [18, 30) lies in tile (row 1, col 1) = index 5, or in strip 1.
    const PixelWindow window{20, 30, 18, 30};
    const size_t keep = tiled ? 5 : 1;
    std::string bytes = ReadBytes(path);
    const auto blocks = DataBlocks(path);
    ASSERT_EQ(blocks.size(), tiled ? 16u : 4u);
    for (size_t i = 0; i < blocks.size(); ++i) {
      if (i == keep) continue;
      for (uint64_t k = 0; k < blocks[i].second; ++k) bytes[blocks[i].first + k] = static_cast<char>(0xA5);
    }
    WriteBytes(path, bytes);
    ExpectSame(ReadTiffDepthWindow(path.string(), window), Crop(Cleaned(depth), window));
    ExpectInputError([&] { ReadTiffDepth(path.string()); },
                     {path.string(), tiled ? "cannot decode tile 0" : "cannot decode strip 0"});
  }
}

TEST(TiffDepthTest, GdalNodataMarksInvalidPixels) {
  TempDir dir;
  DepthMap depth(4, 2, 1, 10.0f);
  depth.at(0, 1) = 0.0f;      // invalid -> written as the nodata value 65535
  depth.at(1, 3) = 65535.5f;  // a valid depth that is not the nodata value
  TiffDepthWriteOptions o;
  o.nodata = 65535.0f;
  const fs::path path = dir / "n.tif";
  WriteTiffDepth(path.string(), depth, o);
  EXPECT_EQ(*ReadTiffDepthInfo(path.string()).nodata, 65535.0);
  // Without the nodata tag, 65535 would be a (valid) depth: check the file really holds it.
  o.nodata.reset();
  DepthMap raw = depth;
  raw.at(0, 1) = 65535.0f;
  WriteTiffDepth((dir / "raw.tif").string(), raw, o);
  EXPECT_EQ(ReadTiffDepth((dir / "raw.tif").string()).at(0, 1), 65535.0f);
  const DepthMap read = ReadTiffDepth(path.string());
  EXPECT_EQ(read.at(0, 1), 0.0f);
  EXPECT_EQ(read.at(1, 3), 65535.5f);
  EXPECT_EQ(read.at(1, 2), 10.0f);

  // A GDAL_NODATA text that is not a number.
  o.nodata = -9999.0f;
  const fs::path bad = dir / "bad_nodata.tif";
  WriteTiffDepth(bad.string(), depth, o);
  std::string bytes = ReadBytes(bad);
  const size_t at = bytes.find(std::string("-9999\0", 6));
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 5, "abcde");
  WriteBytes(bad, bytes);
  ExpectInputError([&] { ReadTiffDepth(bad.string()); }, {bad.string(), "GDAL_NODATA", "abcde", "not a number"});
}

TEST(TiffDepthTest, CorruptAndWrongFilesNameTheFileAndPrintNothing) {
  TempDir dir;
  const fs::path missing = dir / "missing.tif";
  ExpectInputError([&] { ReadTiffDepthInfo(missing.string()); }, {missing.string(), "does not exist"});

  const fs::path text = dir / "text.tif";
  WriteBytes(text, "this is not a TIFF file at all, just some text");
  ExpectInputError([&] { ReadTiffDepthInfo(text.string()); }, {text.string(), "not a readable TIFF"});

  const fs::path empty = dir / "empty.tif";
  WriteBytes(empty, "");
  ExpectInputError([&] { ReadTiffDepth(empty.string()); }, {empty.string(), "not a readable TIFF"});

  const fs::path truncated = dir / "truncated.tif";
  TiffDepthWriteOptions o;
  o.compression = Compression::kNone;
  WriteTiffDepth(truncated.string(), TestDepth(64, 64), o);
  const std::string whole = ReadBytes(truncated);
  WriteBytes(truncated, whole.substr(0, whole.size() / 2));
  ExpectInputError([&] { ReadTiffDepth(truncated.string()); }, {truncated.string()});

  const fs::path u16 = dir / "u16.tif";
  WriteOddTiff(u16, 16, SAMPLEFORMAT_UINT, 1);
  ExpectInputError([&] { ReadTiffDepthInfo(u16.string()); }, {u16.string(), "not float32", "16-bit unsigned integer"});

  const fs::path f64 = dir / "f64.tif";
  WriteOddTiff(f64, 64, SAMPLEFORMAT_IEEEFP, 1);
  ExpectInputError([&] { ReadTiffDepth(f64.string()); }, {f64.string(), "not float32", "64-bit floating point"});

  const fs::path rgb = dir / "rgb.tif";
  WriteOddTiff(rgb, 32, SAMPLEFORMAT_IEEEFP, 3);
  ExpectInputError([&] { ReadTiffDepth(rgb.string()); }, {rgb.string(), "3 bands"});

  const fs::path flipped = dir / "flipped.tif";
  WriteOddTiff(flipped, 32, SAMPLEFORMAT_IEEEFP, 1, ORIENTATION_BOTLEFT);
  ExpectInputError([&] { ReadTiffDepth(flipped.string()); }, {flipped.string(), "Orientation tag is 4"});

  // The good control: the same helper with float32, one band, top-left orientation reads.
  const fs::path good = dir / "good.tif";
  WriteOddTiff(good, 32, SAMPLEFORMAT_IEEEFP, 1, ORIENTATION_TOPLEFT);
  EXPECT_EQ(ReadTiffDepth(good.string()).width, 8);
}

TEST(TiffDepthTest, WriterRejectsBadOptions) {
  TempDir dir;
  TiffDepthWriteOptions o;
  o.tile_size_px = 24;
  EXPECT_THROW(WriteTiffDepth((dir / "a.tif").string(), TestDepth(8, 8), o), Error);
  o = {};
  o.tiled = false;
  o.rows_per_strip = 0;
  EXPECT_THROW(WriteTiffDepth((dir / "b.tif").string(), TestDepth(8, 8), o), Error);
  EXPECT_THROW(WriteTiffDepth((dir / "c.tif").string(), DepthMap()), Error);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace sacfuse
