#pragma once
// A 2D raster with C interleaved channels: value(row, col, c) = data[(row * width + col) * channels + c].
// Depth maps are Raster<float> with 1 channel (z-depth in metres, <= 0 or non-finite = invalid); normal maps
// Raster<float> with 3 channels (unit vectors in the camera frame); images Raster<uint8_t> with 3 channels (RGB).
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/raster_buffer.h"

namespace sacfuse {

template <typename T>
struct Raster {
  int width = 0;
  int height = 0;
  int channels = 1;
  // Large rasters on huge pages, zero when allocated (core/raster_buffer.h).
  std::vector<T, RasterAllocator<T>> data;

  Raster() = default;
  // Every value `fill`. A large raster of zeros is not written: its fresh buffer is zero already.
  Raster(int w, int h, int c = 1, T fill = T{}) : width(w), height(h), channels(c) {
    const size_t n = static_cast<size_t>(w) * h * c;
    if (std::is_arithmetic_v<T> && IsZeroBits(fill) && RasterBufferIsZeroed(n * sizeof(T))) {
      data.resize(n);
    } else {
      data.assign(n, fill);
    }
  }
  // A raster whose every value the caller writes before reading any (a decoder's output): large ones are not
  // written twice. Values not written are unspecified.
  static Raster Uninitialized(int w, int h, int c = 1) {
    Raster r;
    r.width = w;
    r.height = h;
    r.channels = c;
    r.data.resize(static_cast<size_t>(w) * h * c);
    return r;
  }

  T& at(int row, int col, int c = 0) { return data[(static_cast<size_t>(row) * width + col) * channels + c]; }
  const T& at(int row, int col, int c = 0) const {
    return data[(static_cast<size_t>(row) * width + col) * channels + c];
  }
  bool Contains(int row, int col) const { return row >= 0 && col >= 0 && row < height && col < width; }
  bool empty() const { return data.empty(); }
  size_t num_pixels() const { return static_cast<size_t>(width) * height; }

 private:
  static bool IsZeroBits(const T& v) {
    const unsigned char* b = reinterpret_cast<const unsigned char*>(&v);
    for (size_t i = 0; i < sizeof(T); ++i) {
      if (b[i] != 0) return false;
    }
    return true;
  }
};

using DepthMap = Raster<float>;
using NormalMap = Raster<float>;
using RgbImage = Raster<uint8_t>;

inline bool IsValidDepth(float depth) { return depth > 0.0f && depth < 1e30f; }

}  // namespace sacfuse
