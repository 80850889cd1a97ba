#include "tools/sim/reference_cloud.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "io/las_reader.h"
#include "io/las_writer.h"
#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {

std::array<uint16_t, 3> ToRgb16(const Eigen::Vector3f& albedo) {
  std::array<uint16_t, 3> rgb{};
  for (int k = 0; k < 3; ++k) {
    rgb[k] = static_cast<uint16_t>(std::clamp(std::lround(albedo[k] * 255.0f), 0L, 255L) * 257);
  }
  return rgb;
}

}  // namespace

uint64_t WriteSampledReference(const Surface& surface, const Box2d& area, double density, uint64_t key,
                               const std::string& path, const ReferenceProgress& progress) {
  const double spacing = 1.0 / std::sqrt(density);
  const int nx = std::max(1, static_cast<int>(std::round(area.Width() / spacing)));
  const int ny = std::max(1, static_cast<int>(std::round(area.Height() / spacing)));
  const double sx = area.Width() / nx, sy = area.Height() / ny;
  LasWriterOptions options;
  LasWriter writer(path, options);
  const Eigen::Vector3f up(0.0f, 0.0f, 1.0f);
  const int rows_per_chunk = std::max(1, 200000 / nx);
  std::vector<LasPoint> chunk;
  std::vector<uint8_t> ok;
  for (int row0 = 0; row0 < ny; row0 += rows_per_chunk) {
    const int row1 = std::min(ny, row0 + rows_per_chunk);
    chunk.assign(static_cast<size_t>(row1 - row0) * nx, LasPoint());
    ok.assign(chunk.size(), 0);
    tbb::parallel_for(row0, row1, [&](int row) {
      for (int col = 0; col < nx; ++col) {
        const size_t i = static_cast<size_t>(row - row0) * nx + col;
        const uint64_t h = Hash3(key, static_cast<uint64_t>(row), static_cast<uint64_t>(col));
        const double x = area.min.x() + (col + HashToUnit(h)) * sx;
        const double y = area.min.y() + (row + HashToUnit(SplitMix64(h))) * sy;
        const double z = surface.Height(x, y);
        if (!std::isfinite(z)) continue;
        LasPoint& p = chunk[i];
        p.xyz = Eigen::Vector3d(x, y, z);
        p.classification = surface.Class(x, y);
        const Eigen::Vector3f albedo = surface.Albedo(p.xyz, up);
        p.rgb = ToRgb16(albedo);
        p.intensity = static_cast<uint16_t>(
            std::clamp(0.3f * albedo[0] + 0.59f * albedo[1] + 0.11f * albedo[2], 0.0f, 1.0f) * 65535.0f);
        ok[i] = 1;
      }
    });
    size_t n = 0;
    for (size_t i = 0; i < chunk.size(); ++i) {
      if (ok[i]) chunk[n++] = chunk[i];
    }
    writer.WritePoints(chunk.data(), n);
    if (progress) progress(static_cast<size_t>(row1), static_cast<size_t>(ny));
  }
  writer.Close();
  return writer.num_points();
}

uint64_t WriteLasReference(const std::string& las_path, const Surface& surface, const Box2d& area,
                           const std::string& path) {
  LasReader reader(las_path);
  const int format = reader.header().point_format;
  const bool has_rgb = format == 2 || format == 3 || format == 5 || format == 7 || format == 8 || format == 10;
  LasWriterOptions options;
  LasWriter writer(path, options);
  const Eigen::Vector3f up(0.0f, 0.0f, 1.0f);
  std::vector<LasPoint> chunk, kept;
  while (reader.Read(&chunk, 1 << 16) > 0) {
    kept.clear();
    for (LasPoint p : chunk) {
      if (!area.Contains(p.xyz.x(), p.xyz.y())) continue;
      if (!has_rgb) p.rgb = ToRgb16(surface.Albedo(p.xyz, up));
      p.nir = 0;
      kept.push_back(p);
    }
    writer.WritePoints(kept.data(), kept.size());
  }
  writer.Close();
  return writer.num_points();
}

}  // namespace sacfuse::sim
