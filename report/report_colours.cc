#include "report/report_colours.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace sacfuse {

ViewKind ClassifyViewName(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower.find("nadir") != std::string::npos) return ViewKind::kNadir;
  if (lower.find("obl") != std::string::npos) return ViewKind::kOblique;
  return ViewKind::kUnknown;
}

bool ViewKindsKnown(const std::vector<ViewKind>& kinds) {
  return !kinds.empty() && std::none_of(kinds.begin(), kinds.end(), [](ViewKind k) { return k == ViewKind::kUnknown; });
}

Rgb HsvToRgb(double h, double s, double v) {
  h = h - std::floor(h);
  const double hh = h * 6.0;
  const int sector = static_cast<int>(hh) % 6;
  const double f = hh - std::floor(hh);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (sector) {
    case 0: r = v; g = t; b = p; break;
    case 1: r = q; g = v; b = p; break;
    case 2: r = p; g = v; b = t; break;
    case 3: r = p; g = q; b = v; break;
    case 4: r = t; g = p; b = v; break;
    default: r = v; g = p; b = q; break;
  }
  const auto to8 = [](double x) { return static_cast<uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); };
  return {to8(r), to8(g), to8(b)};
}

namespace {

// The k-th colour of a group spanning hues [h0, h0 + span).
Rgb GroupColour(size_t k, double h0, double span) {
  constexpr double kGolden = 0.6180339887498949;
  const double position = std::fmod(static_cast<double>(k) * kGolden, 1.0);
  static constexpr double kValue[3] = {0.92, 0.72, 0.55};
  static constexpr double kSaturation[3] = {0.70, 0.85, 0.75};
  const size_t level = k % 3;
  return HsvToRgb(h0 + span * position, kSaturation[level], kValue[level]);
}

}  // namespace

std::vector<Rgb> ViewColours(const std::vector<ViewKind>& kinds) {
  std::vector<Rgb> colours(kinds.size());
  if (!ViewKindsKnown(kinds)) {
    for (size_t i = 0; i < kinds.size(); ++i) colours[i] = GroupColour(i, 0.0, 1.0);
    return colours;
  }
  size_t nadir = 0, oblique = 0;
  for (size_t i = 0; i < kinds.size(); ++i) {
    // Nadir: hues 0.47..0.80 (cyan, blue, violet); oblique: -0.03..0.30 (red, orange, yellow, green).
    colours[i] = kinds[i] == ViewKind::kNadir ? GroupColour(nadir++, 0.47, 0.33) : GroupColour(oblique++, -0.03, 0.33);
  }
  return colours;
}

}  // namespace sacfuse
