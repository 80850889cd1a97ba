#include "report/report_map_figure.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {

std::vector<float> HillShade(const std::vector<float>& z, int width, int height, double cell_m,
                             const SourceMapStyle& style) {
  std::vector<float> shade(z.size(), 1.0f);
  const double az = style.sun_azimuth_deg * M_PI / 180.0, el = style.sun_elevation_deg * M_PI / 180.0;
  // Light direction (towards the sun) in x east, y north, z up.
  const double lx = std::sin(az) * std::cos(el), ly = std::cos(az) * std::cos(el), lz = std::sin(el);
  const auto index = [width](int r, int c) { return static_cast<size_t>(r) * width + c; };
  const auto z_at = [&](int r, int c) -> float {
    if (r < 0 || c < 0 || r >= height || c >= width) return NAN;
    return z[index(r, c)];
  };
  // Slope along one axis from the neighbours before/after (one-sided when one is missing), per metre.
  const auto slope = [&](float before, float centre, float after) -> double {
    if (!std::isnan(before) && !std::isnan(after)) return (after - before) / (2.0 * cell_m);
    if (!std::isnan(after)) return (after - centre) / cell_m;
    if (!std::isnan(before)) return (centre - before) / cell_m;
    return 0.0;
  };
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const float zc = z_at(r, c);
      if (std::isnan(zc)) continue;
      const double dzdx = slope(z_at(r, c - 1), zc, z_at(r, c + 1));
      const double dzdy = slope(z_at(r + 1, c), zc, z_at(r - 1, c));  // row + 1 is south
      // Surface normal (-dz/dx, -dz/dy, 1), normalised.
      const double n = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
      const double lambert = (-dzdx * lx - dzdy * ly + lz) / n;
      const double f = 1.0 + style.shade_strength * (std::max(0.0, lambert) - lz) / lz;
      shade[index(r, c)] = static_cast<float>(std::clamp(f, 0.35, 1.45));
    }
  }
  return shade;
}

std::vector<float> HillShade(const TopGrid& g, const SourceMapStyle& style) {
  return HillShade(g.top_z, g.width, g.height, g.cell_m, style);
}

RgbImage RenderDsmHillShade(const std::vector<float>& z, int width, int height, double cell_m,
                            const SourceMapStyle& style) {
  RgbImage image(width, height, 3);
  std::vector<float> valid;
  for (const float v : z) {
    if (!std::isnan(v)) valid.push_back(v);
  }
  float lo = 0, hi = 1;
  if (!valid.empty()) {
    const auto at = [&](double q) {
      const size_t k = static_cast<size_t>(q * static_cast<double>(valid.size() - 1));
      std::nth_element(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(k), valid.end());
      return valid[k];
    };
    lo = at(0.02);
    hi = std::max(at(0.98), lo + 1e-3f);
  }
  const std::vector<float> shade = HillShade(z, width, height, cell_m, style);
  // Tint stops: low ground, mid, high.
  const double stops[3][3] = {{86, 140, 84}, {214, 198, 150}, {250, 250, 246}};
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const size_t i = static_cast<size_t>(r) * width + c;
      Rgb rgb = style.empty;
      if (!std::isnan(z[i])) {
        const double t = std::clamp((z[i] - lo) / (hi - lo), 0.0f, 1.0f) * 2.0;
        const int k = std::min(1, static_cast<int>(t));
        const double f = t - k;
        for (int ch = 0; ch < 3; ++ch) {
          const double base = stops[k][ch] * (1 - f) + stops[k + 1][ch] * f;
          rgb[ch] = static_cast<uint8_t>(std::clamp(std::lround(base * shade[i]), 0L, 255L));
        }
      }
      for (int ch = 0; ch < 3; ++ch) image.at(r, c, ch) = rgb[ch];
    }
  }
  return image;
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
