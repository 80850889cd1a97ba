// "Before" counts per view: from the superpixel cache's cluster tables (no depth pixel read), else from the
// depth raster in bands; stale, foreign-sized or corrupt cache files fall back to the raster.
#include "report/report_input_counts.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/superpixels.h"
#include "io/superpixel_io.h"
#include "report/report_test_block.h"
#include "config/output_layout.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

// A depth raster with a known number of valid pixels: every pixel valid but those with (row * 7 + col) % 5 == 0
// (zero), and every 11th of those NaN instead.
DepthMap Depth(int width, int height, uint64_t* valid) {
  DepthMap d(width, height);
  *valid = 0;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const bool invalid = (r * 7 + c) % 5 == 0;
      d.at(r, c) = invalid ? ((r + c) % 11 == 0 ? NAN : 0.0f) : 50.0f + 0.01f * c;
      *valid += invalid ? 0 : 1;
    }
  }
  return d;
}

void WriteCache(const std::string& dir, const std::string& name, const DepthMap& depth) {
  const RgbImage image(depth.width, depth.height, 3, 128);
  SuperpixelOptions options;
  options.region_size_px = 8;
  const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
  const std::string path = SuperpixelCachePath(dir, name);
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteSuperpixels(path, map, SuperpixelOptionsHash(options));
}

TEST(ReportInputCountsTest, CountsFromTheClusterTablesWithoutReadingDepth) {
  testing::TempDir dir;
  testing::MemoryDepthBlock block;
  uint64_t valid0 = 0, valid1 = 0;
  const DepthMap d0 = Depth(64, 48, &valid0), d1 = Depth(40, 600, &valid1);  // 600 rows: several bands
  block.Add(testing::NadirView("nadir/a.jpg", 0, 0, 100, 64, 48, 100), d0);
  block.Add(testing::NadirView("oblique_fwd/b.jpg", 0, 0, 100, 40, 600, 100), d1);
  WriteCache(dir.path().string(), "nadir/a.jpg", d0);  // view 1 has no cache file

  size_t from_rasters = 0;
  const std::vector<uint64_t> counts = ValidDepthPixelsPerView(block, dir.path().string(), &from_rasters);
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts[0], valid0);
  EXPECT_EQ(counts[1], valid1);
  EXPECT_EQ(from_rasters, 1u);
  EXPECT_EQ(block.pixels_read, 40u * 600u);  // only view 1's raster, once
  // The cheap variant reads no raster and leaves uncached views at 0.
  size_t not_cached = 0;
  const std::vector<uint64_t> cheap = ValidDepthPixelsPerView(block, dir.path().string(), &not_cached, false);
  EXPECT_EQ(cheap[0], valid0);
  EXPECT_EQ(cheap[1], 0u);
  EXPECT_EQ(not_cached, 1u);
  EXPECT_EQ(block.pixels_read, 40u * 600u);
}

TEST(ReportInputCountsTest, ForeignSizedOrCorruptCacheFallsBackToTheRaster) {
  testing::TempDir dir;
  testing::MemoryDepthBlock block;
  uint64_t valid0 = 0, valid1 = 0, other = 0;
  const DepthMap d0 = Depth(64, 48, &valid0), d1 = Depth(32, 32, &valid1);
  block.Add(testing::NadirView("a.jpg", 0, 0, 100, 64, 48, 100), d0);
  block.Add(testing::NadirView("b.jpg", 0, 0, 100, 32, 32, 100), d1);
  WriteCache(dir.path().string(), "a.jpg", Depth(48, 48, &other));  // another raster size: not this view's
  WriteCache(dir.path().string(), "b.jpg", d1);
  {  // truncate b's cache file: corrupt
    const std::string path = SuperpixelCachePath(dir.path().string(), "b.jpg");
    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size - 7);
  }
  size_t from_rasters = 0;
  const std::vector<uint64_t> counts = ValidDepthPixelsPerView(block, dir.path().string(), &from_rasters);
  EXPECT_EQ(counts[0], valid0);
  EXPECT_EQ(counts[1], valid1);
  EXPECT_EQ(from_rasters, 2u);
}

TEST(ReportInputCountsTest, CountFromRasterReadsBandsOfTheWholeRaster) {
  testing::MemoryDepthBlock block;
  uint64_t valid = 0;
  block.Add(testing::NadirView("a.jpg", 0, 0, 100, 13, 2 * kValidPixelCountBandRows + 3, 100),
            Depth(13, 2 * kValidPixelCountBandRows + 3, &valid));
  EXPECT_EQ(CountValidDepthPixels(block, block.views()[0]), valid);
  EXPECT_EQ(block.pixels_read, 13u * (2 * kValidPixelCountBandRows + 3));
}

}  // namespace
}  // namespace sacfuse
