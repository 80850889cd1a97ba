// The rasters' buffers (core/raster_buffer.h): large ones start on a huge-page boundary, zero, and hold what is
// written to them through copies, moves and growth; small ones come from the heap; a raster's fill is its values
// whether or not the buffer had to be written.
#include "core/raster_buffer.h"

#include <cstdint>
#include <cmath>
#include <cstring>
#include <numeric>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/raster.h"

namespace sacfuse {
namespace {

bool OnHugePageBoundary(const void* p) { return reinterpret_cast<uintptr_t>(p) % kHugePageBytes == 0; }

TEST(RasterBufferTest, LargeRastersStartOnAHugePageAndKeepTheirValues) {
  // 1100 x 700 floats: 3.08 MB, not a multiple of the huge page.
  DepthMap depth(1100, 700, 1, 7.5f);
  ASSERT_EQ(depth.data.size(), size_t{1100} * 700);
  EXPECT_TRUE(OnHugePageBoundary(depth.data.data()));
  EXPECT_EQ(depth.at(0, 0), 7.5f);
  EXPECT_EQ(depth.at(699, 1099), 7.5f);
  std::iota(depth.data.begin(), depth.data.end(), 0.0f);
  const DepthMap copy = depth;
  EXPECT_TRUE(OnHugePageBoundary(copy.data.data()));
  EXPECT_EQ(copy.data, depth.data);
  EXPECT_EQ(copy.at(699, 1099), 699.0f * 1100 + 1099);
  const float* buffer = depth.data.data();
  const DepthMap moved = std::move(depth);
  EXPECT_EQ(moved.data.data(), buffer);  // a move keeps the buffer
  EXPECT_EQ(moved.data, copy.data);
}

TEST(RasterBufferTest, ZeroFilledRastersAreZeroAtEverySize) {
  // Large ones take the fresh buffer as it is, small ones are written; -0.0f is not +0.0f and is written.
  for (int side : {3, 700, 1500}) {
    for (int round = 0; round < 3; ++round) {  // freed and allocated again: still zero
      DepthMap depth(side, side);
      for (size_t i = 0; i < depth.data.size(); i += 997) ASSERT_EQ(depth.data[i], 0.0f) << side << " " << i;
      ASSERT_EQ(depth.data.back(), 0.0f);
      std::fill(depth.data.begin(), depth.data.end(), 3.0f);  // dirty it before it is freed
    }
    RgbImage image(side, side, 3);
    EXPECT_EQ(image.at(side - 1, side - 1, 2), 0);
    const DepthMap negative(side, side, 1, -0.0f);
    EXPECT_TRUE(std::signbit(negative.data.back())) << side;
  }
}

TEST(RasterBufferTest, UninitializedRastersHaveTheirShapeAndKeepWhatIsWritten) {
  RgbImage image = RgbImage::Uninitialized(2000, 1000, 3);
  EXPECT_EQ(image.width, 2000);
  EXPECT_EQ(image.height, 1000);
  EXPECT_EQ(image.channels, 3);
  ASSERT_EQ(image.data.size(), size_t{2000} * 1000 * 3);
  EXPECT_TRUE(OnHugePageBoundary(image.data.data()));
  std::memset(image.data.data(), 9, image.data.size());
  EXPECT_EQ(image.at(999, 1999, 2), 9);
  const DepthMap small = DepthMap::Uninitialized(4, 2);
  EXPECT_EQ(small.data.size(), size_t{8});
}

TEST(RasterBufferTest, GrowingAcrossTheThresholdKeepsTheValues) {
  std::vector<uint32_t, RasterAllocator<uint32_t>> values;
  const size_t n = kHugePageBytes / sizeof(uint32_t) + 3;  // crosses from the heap to huge pages
  for (size_t i = 0; i < n; ++i) values.push_back(static_cast<uint32_t>(i * 3));
  EXPECT_TRUE(OnHugePageBoundary(values.data()));
  for (size_t i = 0; i < n; i += 4099) ASSERT_EQ(values[i], i * 3) << i;
  EXPECT_EQ(values.back(), (n - 1) * 3);
  values.resize(10);
  values.shrink_to_fit();  // back to a small heap buffer
  EXPECT_EQ(values[9], 27u);
}

TEST(RasterBufferTest, SmallBuffersComeFromTheHeap) {
  RgbImage image(4, 3, 3, 200);
  EXPECT_EQ(image.data.size(), size_t{36});
  EXPECT_EQ(image.at(2, 3, 2), 200);
  void* p = AllocateRasterBuffer(100);
  ASSERT_NE(p, nullptr);
  FreeRasterBuffer(p, 100);
  FreeRasterBuffer(nullptr, kHugePageBytes);  // nothing to free
}

}  // namespace
}  // namespace sacfuse
