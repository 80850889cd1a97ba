#include "report/report_profile_figure.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {

PlotFrame MakePlotFrame(double length_m, double z_min, double z_max, int max_width_px, int min_width_px,
                        int min_height_px, int max_height_px) {
  PlotFrame f;
  f.s_min = 0.0;
  f.s_max = std::max(length_m, 1e-3);
  f.z_min = z_min;
  f.z_max = z_max > z_min ? z_max : z_min + 1.0;
  const double aspect = (f.z_max - f.z_min) / f.s_max;  // height / width at true shape
  f.width_px = max_width_px;
  double height = aspect * max_width_px;
  if (height > max_height_px) {
    f.width_px = std::max(min_width_px, static_cast<int>(std::lround(max_height_px / aspect)));
    height = max_height_px;
  }
  f.height_px = static_cast<int>(std::clamp(std::lround(height), static_cast<long>(min_height_px),
                                            static_cast<long>(max_height_px)));
  return f;
}

void RobustHeightRange(const std::vector<const std::vector<ProfilePoint>*>& sets, double* lo, double* hi) {
  std::vector<float> z;
  for (const auto* set : sets) {
    for (const ProfilePoint& p : *set) z.push_back(p.z_m);
  }
  if (z.empty()) return;
  const auto at = [&](double q) {
    const size_t k = static_cast<size_t>(std::floor(q * (z.size() - 1)));
    std::nth_element(z.begin(), z.begin() + k, z.end());
    return static_cast<double>(z[k]);
  };
  const double a = at(0.005), b = at(0.995);
  const double pad = std::max(1.0, 0.05 * (b - a));
  *lo = a - pad;
  *hi = b + pad;
}

namespace {

void Blend(RgbImage* image, int row, int col, const Rgb& rgb, double alpha) {
  if (!image->Contains(row, col)) return;
  for (int c = 0; c < 3; ++c) {
    uint8_t& v = image->at(row, col, c);
    v = static_cast<uint8_t>(std::lround(v * (1.0 - alpha) + rgb[c] * alpha));
  }
}

void Dot(RgbImage* image, const PlotFrame& f, const ProfilePoint& p, int size, const Rgb& rgb, double alpha) {
  if (p.along_m < f.s_min || p.along_m > f.s_max || p.z_m < f.z_min || p.z_m > f.z_max) return;
  const int col = static_cast<int>(std::floor(f.ColumnOf(p.along_m))) - size / 2;
  const int row = static_cast<int>(std::floor(f.RowOf(p.z_m))) - size / 2;
  for (int dr = 0; dr < size; ++dr) {
    for (int dc = 0; dc < size; ++dc) Blend(image, row + dr, col + dc, rgb, alpha);
  }
}

}  // namespace

RgbImage RenderProfilePanel(const std::vector<ProfilePoint>& points, const std::vector<ProfilePoint>& reference,
                            const std::vector<Rgb>& colours, const PlotFrame& f, const std::vector<double>& grid_z,
                            const ProfileStyle& style) {
  RgbImage image(f.width_px, f.height_px, 3);
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < image.width; ++c) {
      for (int ch = 0; ch < 3; ++ch) image.at(r, c, ch) = style.background[ch];
    }
  }
  for (const double z : grid_z) {
    const int row = static_cast<int>(std::floor(f.RowOf(z)));
    for (int c = 0; c < image.width; ++c) Blend(&image, row, c, style.grid, 1.0);
  }
  for (const ProfilePoint& p : points) {
    const Rgb rgb = p.source_id >= 1 && p.source_id <= colours.size() ? colours[p.source_id - 1] : kUnknownViewColour;
    Dot(&image, f, p, style.dot_px, rgb, style.alpha);
  }
  for (const ProfilePoint& p : reference) Dot(&image, f, p, style.reference_dot_px, style.reference, 1.0);
  return image;
}

}  // namespace sacfuse
