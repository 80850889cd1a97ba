#include "report/report_tile_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "report/report_text.h"

namespace sacfuse {
namespace {

constexpr double kMargin = 4.0;
constexpr double kLegend = 30.0;  // px below the map for its legend

std::string Hex(const Rgb& c) { return HexColour(c[0], c[1], c[2]); }

Box2d TileBox(const ReportTile& t) {
  if (t.has_core) return t.core;
  Box2d b;
  b.min = Eigen::Vector2d(t.ix, t.iy);
  b.max = Eigen::Vector2d(t.ix + 1, t.iy + 1);
  return b;
}

struct Fit {
  Box2d world;
  double scale = 1.0;  // px per world unit
  double width = 0.0, height = 0.0;
  double X(double x) const { return kMargin + (x - world.min.x()) * scale; }
  double Y(double y) const { return kMargin + (world.max.y() - y) * scale; }
};

Fit FitBox(const Box2d& world, double width_px, double max_height_px) {
  Fit f;
  f.world = world;
  const double ww = std::max(1e-9, world.max.x() - world.min.x()), wh = std::max(1e-9, world.max.y() - world.min.y());
  f.scale = std::min((width_px - 2 * kMargin) / ww, (max_height_px - 2 * kMargin) / wh);
  f.width = ww * f.scale + 2 * kMargin;
  f.height = wh * f.scale + 2 * kMargin;
  return f;
}

void OpenSvg(std::ostringstream& s, double w, double h) {
  s << "<svg class='chart' width='" << Fixed(w, 0) << "' height='" << Fixed(h, 0)
    << "' viewBox='0 0 " << Fixed(w, 0) << " " << Fixed(h, 0) << "'>\n";
}

}  // namespace

const char* TileStatusName(TileStatus status) {
  switch (status) {
    case TileStatus::kDone: return "done";
    case TileStatus::kFailed: return "failed";
    default: return "pending";
  }
}

Rgb TileStatusColour(TileStatus status) {
  switch (status) {
    case TileStatus::kDone: return {102, 187, 106};
    case TileStatus::kFailed: return {229, 57, 53};
    default: return {207, 207, 207};
  }
}

Rgb TimeRampColour(double t, double t_min, double t_max) {
  static constexpr double kStops[3][3] = {{255, 241, 168}, {244, 128, 36}, {127, 0, 0}};
  const double u = t_max > t_min ? std::clamp((t - t_min) / (t_max - t_min), 0.0, 1.0) : 0.0;
  const int k = u < 0.5 ? 0 : 1;
  const double f = u < 0.5 ? u / 0.5 : (u - 0.5) / 0.5;
  Rgb out;
  for (int c = 0; c < 3; ++c) out[c] = static_cast<uint8_t>(std::lround(kStops[k][c] * (1 - f) + kStops[k + 1][c] * f));
  return out;
}

std::string TileMapSvg(const std::vector<ReportTile>& tiles, TileColouring colouring, double width_px,
                       double max_height_px) {
  Box2d world;
  double t_min = 1e300, t_max = -1e300;
  for (const ReportTile& t : tiles) {
    world.Extend(TileBox(t));
    if (t.status == TileStatus::kDone) {
      t_min = std::min(t_min, t.seconds);
      t_max = std::max(t_max, t.seconds);
    }
  }
  std::ostringstream s;
  if (tiles.empty()) {
    OpenSvg(s, width_px, 40);
    s << "<text x='8' y='24' class='lbl'>no tiles with views</text></svg>";
    return s.str();
  }
  const Fit fit = FitBox(world, width_px, max_height_px - kLegend);
  OpenSvg(s, std::max(fit.width, 260.0), fit.height + kLegend);
  for (const ReportTile& t : tiles) {
    const Box2d b = TileBox(t);
    const double x = fit.X(b.min.x()), y = fit.Y(b.max.y());
    const double w = (b.max.x() - b.min.x()) * fit.scale, h = (b.max.y() - b.min.y()) * fit.scale;
    Rgb fill = TileStatusColour(t.status);
    if (colouring == TileColouring::kTime) {
      fill = t.status == TileStatus::kDone ? TimeRampColour(t.seconds, t_min, t_max) : TileStatusColour(TileStatus::kPending);
    }
    const bool outline_red = colouring == TileColouring::kTime && t.status == TileStatus::kFailed;
    s << "<g class='tile " << TileStatusName(t.status) << "'><title>tile " << EscapeHtml(t.id) << ": "
      << TileStatusName(t.status);
    if (t.status == TileStatus::kDone) {
      s << ", " << GroupedInteger(t.points) << " points, " << t.views << " views, " << Duration(t.seconds)
        << ", peak RSS " << Fixed(t.peak_rss_mib, 0) << " MiB";
    } else if (!t.reason.empty()) {
      s << ": " << EscapeHtml(t.reason);
    }
    if (t.memory_estimate_bytes > 0) s << ", estimate " << Fixed(t.memory_estimate_bytes / 1048576.0, 0) << " MiB";
    s << "</title><rect x='" << Fixed(x, 2) << "' y='" << Fixed(y, 2) << "' width='" << Fixed(w, 2) << "' height='"
      << Fixed(h, 2) << "' fill='" << Hex(fill) << "' stroke='" << (outline_red ? "#e53935" : "#ffffff")
      << "' stroke-width='" << (outline_red ? 2 : 1) << "'/>";
    const double font = std::min(12.0, std::min(w / (0.62 * std::max<size_t>(3, t.id.size())), h * 0.45));
    if (font >= 5.0) {
      const bool dark = 0.299 * fill[0] + 0.587 * fill[1] + 0.114 * fill[2] < 110.0;
      s << "<text x='" << Fixed(x + w / 2, 2) << "' y='" << Fixed(y + h / 2 + font * 0.35, 2)
        << "' text-anchor='middle' class='tid' style='font-size:" << Fixed(font, 1) << "px" << (dark ? ";fill:#fff" : "")
        << "'>" << EscapeHtml(t.id) << "</text>";
    }
    s << "</g>\n";
  }
  // Legend.
  const double ly = fit.height + 8;
  if (colouring == TileColouring::kStatus) {
    double x = kMargin;
    for (const TileStatus st : {TileStatus::kDone, TileStatus::kFailed, TileStatus::kPending}) {
      size_t n = 0;
      for (const ReportTile& t : tiles) n += t.status == st ? 1 : 0;
      s << "<rect x='" << Fixed(x, 1) << "' y='" << Fixed(ly, 1) << "' width='12' height='12' fill='"
        << Hex(TileStatusColour(st)) << "'/><text x='" << Fixed(x + 16, 1) << "' y='" << Fixed(ly + 10, 1)
        << "' class='lbl'>" << TileStatusName(st) << " (" << n << ")</text>";
      x += 88;
    }
  } else if (t_max >= t_min) {
    s << "<defs><linearGradient id='timeramp'>";
    for (int k = 0; k <= 4; ++k) {
      s << "<stop offset='" << k * 25 << "%' stop-color='" << Hex(TimeRampColour(k / 4.0, 0, 1)) << "'/>";
    }
    s << "</linearGradient></defs><text x='" << Fixed(kMargin, 1) << "' y='" << Fixed(ly + 10, 1)
      << "' class='lbl'>" << Duration(t_min) << "</text><rect x='" << Fixed(kMargin + 52, 1) << "' y='"
      << Fixed(ly, 1) << "' width='120' height='12' fill='url(#timeramp)'/><text x='" << Fixed(kMargin + 178, 1)
      << "' y='" << Fixed(ly + 10, 1) << "' class='lbl'>" << Duration(t_max) << "</text>";
  } else {
    s << "<text x='" << Fixed(kMargin, 1) << "' y='" << Fixed(ly + 10, 1) << "' class='lbl'>no tile done yet</text>";
  }
  s << "\n</svg>";
  return s.str();
}

std::string UntiledExtentSvg(const Box2d& extent, double width_px, double max_height_px) {
  std::ostringstream s;
  if (extent.IsEmpty()) {
    OpenSvg(s, width_px, 40);
    s << "<text x='8' y='24' class='lbl'>untiled (no extent: the run wrote no cloud)</text></svg>";
    return s.str();
  }
  const Fit fit = FitBox(extent, width_px, max_height_px);
  OpenSvg(s, fit.width, fit.height);
  const double w = fit.width - 2 * kMargin, h = fit.height - 2 * kMargin;
  s << "<rect x='" << kMargin << "' y='" << kMargin << "' width='" << Fixed(w, 2) << "' height='" << Fixed(h, 2)
    << "' fill='" << Hex(TileStatusColour(TileStatus::kDone)) << "' stroke='#fff'/>"
    << "<text x='" << Fixed(fit.width / 2, 1) << "' y='" << Fixed(fit.height / 2 - 4, 1)
    << "' text-anchor='middle' class='tid' style='font-size:16px'>untiled</text>"
    << "<text x='" << Fixed(fit.width / 2, 1) << "' y='" << Fixed(fit.height / 2 + 14, 1)
    << "' text-anchor='middle' class='tid' style='font-size:12px'>"
    << Fixed(extent.max.x() - extent.min.x(), 1) << " m × " << Fixed(extent.max.y() - extent.min.y(), 1)
    << " m</text>\n</svg>";
  return s.str();
}

}  // namespace sacfuse
