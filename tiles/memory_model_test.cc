#include "tiles/memory_model.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "tiles/tile_worker.h"

namespace sacfuse {
namespace {

TEST(MemoryModelTest, SuperpixelViewsInFlightIsOnePerThreadWithinTheBudget) {
  BlockPixels pixels;
  pixels.depth_pixels = {1000000, 4000000};  // the largest view decides: 4 Mpx
  pixels.image_pixels = {1000000, 4000000};
  const uint64_t per_view = 4000000 * kSuperpixelPassBytesPerDepthPixel + 4000000 * kBytesPerImagePixel;
  EXPECT_EQ(SuperpixelPassBytes(pixels), kProcessBaseBytes + per_view);
  const uint64_t pass = SuperpixelPassBytes(pixels);
  // The tiled pass with room for ten more such views: one per thread.
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, pass + 10 * per_view, 2, pass), 2u);
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, pass + 10 * per_view, 16, pass), 11u);
  // Room for 1.5 more: two.
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, pass + 3 * per_view / 2, 8, pass), 2u);
  // An untiled run holding nearly the whole budget: one at a time, also when the budget is already exceeded.
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, 8 * per_view, 8, 8 * per_view - per_view / 2), 1u);
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, pass / 2, 8, pass), 1u);
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, pass + 10 * per_view, 0, pass), 1u);
}

TEST(MemoryModelTest, ByteSizesShowTheirUnit) {
  EXPECT_EQ(ByteSizeText(0), "0 B");
  EXPECT_EQ(ByteSizeText(700), "700 B");
  EXPECT_EQ(ByteSizeText(512 * 1024), "512 KiB");
  EXPECT_EQ(ByteSizeText(3 * kMiB + kMiB / 2), "3.5 MiB");
  EXPECT_EQ(ByteSizeText(5 * kGiB / 4), "1.25 GiB");
}

// Issue 50: "windows need ~0.00 GiB, more than the 0.00 GiB that resources.memory_gb = 0.135 leaves".
TEST(MemoryModelTest, OutOfMemoryGuardNamesSizesThatShow) {
  JobConfig config;
  config.resources.memory_gb = 0.135;
  PlannedTile tile;
  tile.id = "3_4";
  tile.views.resize(12);
  std::string err;
  try {
    CheckTileFitsBudget(tile, 3 * kMiB + kMiB / 2, config);
  } catch (const Error& e) {
    err = e.what();
  }
  EXPECT_NE(err.find("tile 3_4: out-of-memory guard: its 12 views' windows need ~3.5 MiB, more than "), std::string::npos)
      << err;
  EXPECT_NE(err.find("resources.memory_gb = 0.135 (138.2 MiB) leaves for tiles after 128.0 MiB for the process"),
            std::string::npos) << err;
  EXPECT_EQ(err.find("0.00 GiB"), std::string::npos) << err;
  EXPECT_NO_THROW(CheckTileFitsBudget(tile, 0, config));
}

}  // namespace
}  // namespace sacfuse
