#include "tools/sim/truth_ortho.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/cell_window.h"
#include "io/gdal_raster.h"

namespace sacfuse::sim {

size_t WriteTruthOrtho(const Surface& surface, const Box2d& area, const Lighting& lighting, double cell_m,
                       const std::string& crs_wkt, const std::string& path) {
  constexpr int kSamples = 4;  // per cell side
  const CellWindow w = CellWindowCovering(area, cell_m);
  const size_t n = w.size();
  std::vector<uint8_t> data(4 * n, 0);
  const double step = cell_m / kSamples, h = 0.25 * step;
  tbb::parallel_for(int64_t{0}, w.rows, [&](int64_t r) {
    const int64_t row = w.row0 + w.rows - 1 - r;
    for (int64_t col = w.col0; col < w.col0 + w.cols; ++col) {
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      int count = 0;
      for (int sy = 0; sy < kSamples; ++sy) {
        for (int sx = 0; sx < kSamples; ++sx) {
          const double x = CellEdge(col, cell_m) + (sx + 0.5) * step, y = CellEdge(row, cell_m) + (sy + 0.5) * step;
          const double z = surface.Height(x, y);
          const double zx0 = surface.Height(x - h, y), zx1 = surface.Height(x + h, y);
          const double zy0 = surface.Height(x, y - h), zy1 = surface.Height(x, y + h);
          if (!std::isfinite(z) || !std::isfinite(zx0 + zx1 + zy0 + zy1)) continue;
          const Eigen::Vector3f normal =
              Eigen::Vector3d(-(zx1 - zx0) / (2 * h), -(zy1 - zy0) / (2 * h), 1.0).normalized().cast<float>();
          sum += surface.Albedo(Eigen::Vector3d(x, y, z), normal) * lighting.Shade(normal) * 255.0f;
          ++count;
        }
      }
      if (count == 0) continue;
      const size_t i = w.Index(col, row);
      for (int c = 0; c < 3; ++c) {
        data[c * n + i] = static_cast<uint8_t>(std::clamp(std::lround(sum[c] / count), 0L, 255L));
      }
      data[3 * n + i] = 255;
    }
  });
  RasterFormat format;
  format.bands = 4;
  format.type = RasterSampleType::kByte;
  format.crs_wkt = crs_wkt;
  format.rgba = true;
  WriteRasterFile(path, w, format, data.data(), RasterLayout::kCog);
  return n;
}

}  // namespace sacfuse::sim
