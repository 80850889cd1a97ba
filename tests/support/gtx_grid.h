#pragma once
// A geoid grid in NOAA's GTX format, made by hand for tests of vertical transformations (PROJ reads GTX): a
// 40-byte big-endian header (south-west latitude and longitude, latitude and longitude spacing in degrees, rows,
// columns) and the float32 values, big-endian, row by row from the south. A file named as the grid PROJ's database
// gives for an operation (its old name, e.g. RAF18.gtx for fr_ign_RAF18.tif) in a folder on PROJ's search path
// stands in for the real model.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace sacfuse::testing {

// Geoid height(lat, lon) = base_m + per_deg_lat_m * (lat - south_deg) over the grid (a tilted plane: bilinear
// interpolation reproduces it exactly).
inline void WriteGtxGrid(const std::filesystem::path& path, double south_deg, double west_deg, double step_deg,
                         int rows, int cols, double base_m, double per_deg_lat_m = 0.0) {
  std::ofstream out(path, std::ios::binary);
  auto put_be = [&](const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) out.put(static_cast<char>(b[n - 1 - i]));
  };
  for (const double v : {south_deg, west_deg, step_deg, step_deg}) put_be(&v, 8);
  for (const int32_t v : {static_cast<int32_t>(rows), static_cast<int32_t>(cols)}) put_be(&v, 4);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const float v = static_cast<float>(base_m + per_deg_lat_m * r * step_deg);
      put_be(&v, 4);
    }
  }
}

}  // namespace sacfuse::testing
