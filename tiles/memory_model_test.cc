#include "tiles/memory_model.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sacfuse
