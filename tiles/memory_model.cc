#include "tiles/memory_model.h"

#include <cstdio>

#include <algorithm>
#include <cmath>


namespace sacfuse {

uint64_t BlockPixels::total_depth_pixels() const {
  uint64_t n = 0;
  for (const uint64_t p : depth_pixels) n += p;
  return n;
}

uint64_t BlockPixels::total_image_pixels() const {
  uint64_t n = 0;
  for (const uint64_t p : image_pixels) n += p;
  return n;
}

BlockPixels MeasureBlockPixels(const DepthBlock& input) {
  BlockPixels out;
  for (const View& view : input.views()) {
    const DepthRasterSize size = input.DepthSize(view);
    out.depth_pixels.push_back(static_cast<uint64_t>(size.width) * size.height);
    out.image_pixels.push_back(static_cast<uint64_t>(view.camera.width) * view.camera.height);
  }
  return out;
}

uint64_t MemoryBudgetBytes(double memory_gb) { return static_cast<uint64_t>(std::llround(memory_gb * kGiB)); }

uint64_t ClusterCacheBudgetBytes(uint64_t budget_bytes) { return std::min<uint64_t>(256 * kMiB, budget_bytes / 16); }

std::string ByteSizeText(uint64_t bytes) {
  char text[32];
  if (bytes >= kGiB) {
    std::snprintf(text, sizeof(text), "%.2f GiB", static_cast<double>(bytes) / kGiB);
  } else if (bytes >= kMiB) {
    std::snprintf(text, sizeof(text), "%.1f MiB", static_cast<double>(bytes) / kMiB);
  } else if (bytes >= 1024) {
    std::snprintf(text, sizeof(text), "%.0f KiB", static_cast<double>(bytes) / 1024);
  } else {
    std::snprintf(text, sizeof(text), "%llu B", static_cast<unsigned long long>(bytes));
  }
  return text;
}

uint64_t TileMemoryPoolBytes(uint64_t budget_bytes) {
  const uint64_t reserved = kProcessBaseBytes + ClusterCacheBudgetBytes(budget_bytes);
  return budget_bytes > reserved ? budget_bytes - reserved : 0;
}

uint64_t TileBytes(uint64_t window_pixels) { return window_pixels * kTileBytesPerWindowPixel; }

uint64_t UntiledSacBytes(const BlockPixels& pixels) {
  return kProcessBaseBytes + pixels.total_depth_pixels() * kUntiledBytesPerDepthPixel +
         pixels.total_image_pixels() * kBytesPerImagePixel;
}

namespace {

// The superpixel pass's memory for its largest view.
uint64_t LargestViewPassBytes(const BlockPixels& pixels) {
  uint64_t peak = 0;
  for (size_t v = 0; v < pixels.depth_pixels.size(); ++v) {
    peak = std::max(peak, pixels.depth_pixels[v] * kSuperpixelPassBytesPerDepthPixel +
                              pixels.image_pixels[v] * kBytesPerImagePixel);
  }
  return peak;
}

}  // namespace

uint64_t SuperpixelPassBytes(const BlockPixels& pixels) { return kProcessBaseBytes + LargestViewPassBytes(pixels); }

size_t SuperpixelViewsInFlight(const BlockPixels& pixels, uint64_t budget_bytes, size_t threads, uint64_t held_bytes) {
  const uint64_t per_view = std::max<uint64_t>(1, LargestViewPassBytes(pixels));
  const uint64_t room = budget_bytes > held_bytes ? budget_bytes - held_bytes : 0;
  const uint64_t more = std::min<uint64_t>(threads > 0 ? threads - 1 : 0, room / per_view);
  return static_cast<size_t>(1 + more);
}

}  // namespace sacfuse
