#include "report/report_map_figure.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {

std::vector<float> HillShade(const TopGrid& g, const SourceMapStyle& style) {
  std::vector<float> shade(g.num_cells(), 1.0f);
  const double az = style.sun_azimuth_deg * M_PI / 180.0, el = style.sun_elevation_deg * M_PI / 180.0;
  // Light direction (towards the sun) in x east, y north, z up.
  const double lx = std::sin(az) * std::cos(el), ly = std::cos(az) * std::cos(el), lz = std::sin(el);
  const auto z_at = [&](int r, int c) -> float {
    if (r < 0 || c < 0 || r >= g.height || c >= g.width) return NAN;
    return g.top_z[g.Index(r, c)];
  };
  // Slope along one axis from the neighbours before/after (one-sided when one is missing), per metre.
  const auto slope = [&](float before, float centre, float after) -> double {
    if (!std::isnan(before) && !std::isnan(after)) return (after - before) / (2.0 * g.cell_m);
    if (!std::isnan(after)) return (after - centre) / g.cell_m;
    if (!std::isnan(before)) return (centre - before) / g.cell_m;
    return 0.0;
  };
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      const float z = z_at(r, c);
      if (std::isnan(z)) continue;
      const double dzdx = slope(z_at(r, c - 1), z, z_at(r, c + 1));
      const double dzdy = slope(z_at(r + 1, c), z, z_at(r - 1, c));  // row + 1 is south
      // Surface normal (-dz/dx, -dz/dy, 1), normalised.
      const double n = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
      const double lambert = (-dzdx * lx - dzdy * ly + lz) / n;
      const double f = 1.0 + style.shade_strength * (std::max(0.0, lambert) - lz) / lz;
      shade[g.Index(r, c)] = static_cast<float>(std::clamp(f, 0.35, 1.45));
    }
  }
  return shade;
}

RgbImage RenderSourceMap(const TopGrid& g, const std::vector<Rgb>& colours, const SourceMapStyle& style) {
  const int k = std::max(1, style.pixels_per_cell);
  RgbImage image(g.width * k, g.height * k, 3);
  const std::vector<float> shade = HillShade(g, style);
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      const size_t i = g.Index(r, c);
      Rgb rgb = style.empty;
      if (g.source_id[i] != 0 || !std::isnan(g.top_z[i])) {
        const uint16_t id = g.source_id[i];
        const Rgb base = id >= 1 && id <= colours.size() ? colours[id - 1] : kUnknownViewColour;
        for (int ch = 0; ch < 3; ++ch) {
          const double v = base[ch] * shade[i];
          rgb[ch] = static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L));
        }
      }
      for (int dr = 0; dr < k; ++dr) {
        for (int dc = 0; dc < k; ++dc) {
          for (int ch = 0; ch < 3; ++ch) image.at(r * k + dr, c * k + dc, ch) = rgb[ch];
        }
      }
    }
  }
  return image;
}

int PixelsPerCellFor(const TopGrid& grid, int target_px) {
  const int longest = std::max(1, std::max(grid.width, grid.height));
  return std::max(1, target_px / longest);
}

}  // namespace sacfuse
