#pragma once
// A north-up boolean raster in the project CRS, e.g. the evaluation mask "seen by at least two views".
// Cell (row, col) covers x in [origin_x + col*cell, origin_x + (col+1)*cell) and
// y in (origin_y - (row+1)*cell, origin_y - row*cell]: origin is the NORTH-WEST corner, rows go south.
#include <cmath>
#include <cstdint>
#include <vector>

namespace sacfuse {

struct GeoMask {
  double origin_x = 0.0;      // west edge, metres
  double origin_y = 0.0;      // north edge, metres
  double cell_size_m = 1.0;   // metres
  int width = 0;
  int height = 0;
  std::vector<uint8_t> cells;  // row-major, non-zero = inside

  bool Contains(double x, double y) const {
    const double col = std::floor((x - origin_x) / cell_size_m);
    const double row = std::floor((origin_y - y) / cell_size_m);
    if (col < 0 || row < 0 || col >= width || row >= height) return false;
    return cells[static_cast<size_t>(row) * width + static_cast<size_t>(col)] != 0;
  }
};

}  // namespace sacfuse
