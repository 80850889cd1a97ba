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
  // Room for ten such views: one per thread.
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, kProcessBaseBytes + 10 * per_view, 2), 2u);
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, kProcessBaseBytes + 10 * per_view, 16), 10u);
  // Room for 2.5 views: two.
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, kProcessBaseBytes + 5 * per_view / 2, 8), 2u);
  // No room at all still loads one at a time (the run refuses a budget below one view elsewhere).
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, kProcessBaseBytes / 2, 8), 1u);
  EXPECT_EQ(SuperpixelViewsInFlight(pixels, kProcessBaseBytes + 10 * per_view, 0), 1u);
}

}  // namespace
}  // namespace sacfuse
