#pragma once
// A half-open rectangle of a raster's pixels: what a tile reads of a view's depth, superpixel and colour rasters.
#include <algorithm>
#include <cstddef>
#include <string>

namespace sacfuse {

// Rows [row_begin, row_end), cols [col_begin, col_end) of a raster.
struct PixelWindow {
  int row_begin = 0, row_end = 0;
  int col_begin = 0, col_end = 0;
  int width() const { return col_end - col_begin; }
  int height() const { return row_end - row_begin; }
  size_t num_pixels() const { return static_cast<size_t>(width()) * height(); }
  // Whether the window is non-empty and inside a raster of width x height.
  bool FitsIn(int raster_width, int raster_height) const {
    return row_begin >= 0 && col_begin >= 0 && row_begin < row_end && col_begin < col_end &&
           row_end <= raster_height && col_end <= raster_width;
  }
  bool operator==(const PixelWindow& o) const {
    return row_begin == o.row_begin && row_end == o.row_end && col_begin == o.col_begin && col_end == o.col_end;
  }
};

// The square of pixels within `radius` (Chebyshev) of (row, col), clipped to a raster of width x height.
inline PixelWindow SquareAround(int row, int col, int radius, int raster_width, int raster_height) {
  return {std::max(0, row - radius), std::min(raster_height, row + radius + 1), std::max(0, col - radius),
          std::min(raster_width, col + radius + 1)};
}

// "rows [a, b) x cols [c, d)" for messages.
inline std::string PixelWindowText(const PixelWindow& w) {
  return "rows [" + std::to_string(w.row_begin) + ", " + std::to_string(w.row_end) + ") x cols [" +
         std::to_string(w.col_begin) + ", " + std::to_string(w.col_end) + ")";
}

}  // namespace sacfuse
