#pragma once
// A 2D raster with C interleaved channels: value(row, col, c) = data[(row * width + col) * channels + c].
// Depth maps are Raster<float> with 1 channel (z-depth in metres, <= 0 or non-finite = invalid); normal maps
// Raster<float> with 3 channels (unit vectors in the camera frame); images Raster<uint8_t> with 3 channels (RGB).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sacfuse {

template <typename T>
struct Raster {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<T> data;

  Raster() = default;
  Raster(int w, int h, int c = 1, T fill = T{})
      : width(w), height(h), channels(c), data(static_cast<size_t>(w) * h * c, fill) {}

  T& at(int row, int col, int c = 0) { return data[(static_cast<size_t>(row) * width + col) * channels + c]; }
  const T& at(int row, int col, int c = 0) const {
    return data[(static_cast<size_t>(row) * width + col) * channels + c];
  }
  bool Contains(int row, int col) const { return row >= 0 && col >= 0 && row < height && col < width; }
  bool empty() const { return data.empty(); }
  size_t num_pixels() const { return static_cast<size_t>(width) * height; }
};

using DepthMap = Raster<float>;
using NormalMap = Raster<float>;
using RgbImage = Raster<uint8_t>;

inline bool IsValidDepth(float depth) { return depth > 0.0f && depth < 1e30f; }

}  // namespace sacfuse
