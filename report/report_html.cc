#include "report/report_html.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>
#include <utility>

#include "config/version.h"
#include "report/report_histogram.h"
#include "report/report_text.h"
#include "report/report_tile_map.h"

namespace sacfuse {
namespace {

constexpr double kMapDisplayPx = 760.0;     // map width on the page
constexpr double kDsmDisplayPx = 360.0;     // the DSM thumbnail's width
constexpr double kPanelAxisLeft = 52.0;     // px left of a profile panel for the z axis
constexpr double kPanelAxisBottom = 34.0;   // px below it for the distance axis

const char* kCss = R"(
:root{--ink:#1d2330;--muted:#5f6b7a;--line:#e3e6eb;--card:#f6f8fa;--accent:#2f6fb3}
*{box-sizing:border-box}
body{margin:0;font:14px/1.45 "DejaVu Sans",Verdana,Arial,sans-serif;color:var(--ink);background:#fff}
main{max-width:1200px;margin:0 auto;padding:18px 28px 40px}
header{border-bottom:3px solid var(--accent);padding-bottom:10px;margin-bottom:14px}
h1{font-size:24px;margin:0 0 4px}
h2{font-size:18px;margin:26px 0 6px;padding-top:10px;border-top:1px solid var(--line)}
h3{font-size:15px;margin:14px 0 4px}
.sub{color:var(--muted);font-size:13px}
.cards{display:flex;flex-wrap:wrap;gap:10px;margin:12px 0}
.card{background:var(--card);border:1px solid var(--line);border-radius:6px;padding:8px 14px;min-width:128px}
.card .v{font-size:20px;font-weight:bold}
.card .k{color:var(--muted);font-size:12px}
.row{display:flex;gap:22px;align-items:flex-start;flex-wrap:wrap}
.caption{color:var(--muted);font-size:12.5px;margin:4px 0 8px;max-width:1140px}
.legend{flex:1;min-width:280px;font-size:12px}
.legend .grp{font-weight:bold;margin:8px 0 4px}
.sw{display:inline-flex;align-items:center;margin:1px 8px 1px 0;white-space:nowrap}
.sw i{display:inline-block;width:11px;height:11px;margin-right:4px;border:1px solid rgba(0,0,0,.25)}
table{border-collapse:collapse;font-size:13px;margin:6px 0}
td,th{border-bottom:1px solid var(--line);padding:3px 10px;text-align:left;vertical-align:top}
th{background:var(--card)}
td.n,th.n{text-align:right;font-variant-numeric:tabular-nums}
.warn{background:#fff4e5;border:1px solid #f0c36d;border-radius:6px;padding:8px 12px;margin:10px 0}
.note{background:var(--card);border-left:3px solid var(--accent);padding:6px 10px;margin:8px 0}
pre{background:var(--card);border:1px solid var(--line);padding:10px;font-size:12px;overflow:auto;max-height:480px}
svg.chart text,svg .lbl,svg .tick{font-family:"DejaVu Sans",Verdana,Arial,sans-serif}
svg .lbl{font-size:12px;fill:#333}
svg .tick{font-size:11px;fill:#444}
svg .tid{fill:#1d2330}
.tables{display:flex;gap:28px;flex-wrap:wrap}
details summary{cursor:pointer;color:var(--accent)}
)";

std::string Hex(const Rgb& c) { return HexColour(c[0], c[1], c[2]); }

uint64_t SumBefore(const ReportData& d) {
  uint64_t n = 0;
  for (const ViewCounts& v : d.run.views) n += v.before;
  return n;
}

// Points in: the valid depth pixels of all views (run_report's input_points, or the per-view sum).
uint64_t PointsIn(const ReportData& d) { return d.run.input_points > 0 ? d.run.input_points : SumBefore(d); }
uint64_t PointsOut(const ReportData& d) { return d.cloud.exists ? d.cloud.points : d.run.output_points; }

std::string Card(const std::string& value, const std::string& key) {
  return "<div class='card'><div class='v'>" + value + "</div><div class='k'>" + key + "</div></div>";
}

std::string Header(const ReportData& d) {
  std::ostringstream s;
  s << "<header><h1>sacfuse run report</h1><div class='sub'>" << EscapeHtml(d.output_dir);
  if (!d.run.method.empty()) s << " &middot; method <b>" << EscapeHtml(d.run.method) << "</b>";
  if (!d.run.version.empty()) s << " &middot; run by " << EscapeHtml(d.run.version);
  s << " &middot; report written " << EscapeHtml(d.generated_at) << " by " << EscapeHtml(FullVersionString())
    << "</div></header>\n";
  return s.str();
}

std::string Warnings(const ReportData& d) {
  std::ostringstream s;
  if (!d.run.failed_tiles.empty()) {
    s << "<div class='warn'><b>" << d.run.failed_tiles.size()
      << " tiles failed; " << d.cloud.name << " was not merged.</b> See the tile map below and rerun them with "
      << "<code>sacfuse run CONFIG --tiles ID,...</code>.</div>\n";
  }
  for (const std::string& w : d.run.input_warnings) {
    s << "<div class='warn'><b>Input:</b> " << EscapeHtml(w) << "</div>\n";
  }
  for (const std::string& w : d.warnings) s << "<div class='warn'>" << EscapeHtml(w) << "</div>\n";
  return s.str();
}

std::string Summary(const ReportData& d) {
  std::ostringstream s;
  const uint64_t in = PointsIn(d), out = PointsOut(d);
  s << "<div class='cards'>";
  s << Card(ShortCount(static_cast<double>(in)), "points in (valid depth pixels)");
  s << Card(ShortCount(static_cast<double>(out)), "points out (" + d.cloud.name + ")");
  if (in > 0) s << Card(Percent(RedundancyRemoved(in, out)), "redundancy removed (1 &minus; out/in)");
  s << Card(std::to_string(d.run.views.size()), "views");
  if (d.run.present) {
    s << Card(Duration(d.run.wall_seconds), "wall time");
    s << Card(Fixed(d.run.peak_rss_mib, 0) + " MiB", "peak RSS");
  }
  if (d.eval.present) {
    for (const ReportEvalScore& e : d.eval.scores) {
      s << Card(Percent(e.f1), "F1 at &tau; = " + TickLabel(e.tau_m, 0.01) + " m");
    }
  }
  s << "</div>\n";
  return s.str();
}

// --- 1. Source-view map -------------------------------------------------------------------------------------

double NiceLength(double max_m) {
  double best = 1e-3;
  for (double mag = 1e-3; mag <= 1e6; mag *= 10) {
    for (const double m : {1.0, 2.0, 5.0}) {
      if (m * mag <= max_m) best = m * mag;
    }
  }
  return best;
}

std::string MapSvg(const MapFigure& m, const ProfileFigure& p, double display_w = kMapDisplayPx) {
  std::ostringstream s;
  const double w = m.width_px, h = m.height_px;
  // display_w: small maps are enlarged (pixelated), large ones reduced
  s << "<svg width='" << Fixed(display_w, 0) << "' height='"
    << Fixed(display_w * h / w, 0) << "' viewBox='0 0 " << Fixed(w, 0) << " " << Fixed(h, 0) << "'>"
    << "<image href='" << EscapeHtml(m.file) << "' x='0' y='0' width='" << Fixed(w, 0) << "' height='" << Fixed(h, 0)
    << "' style='image-rendering:pixelated'/>"
    << "<rect x='0.5' y='0.5' width='" << Fixed(w - 1, 1) << "' height='" << Fixed(h - 1, 1)
    << "' fill='none' stroke='#999'/>\n";
  const double u = w / display_w;  // picture px per displayed px: keeps overlays the same size on the page
  const auto px = [&](double x) { return (x - m.x_min) / m.metres_per_px; };
  const auto py = [&](double y) { return (m.y_max - y) / m.metres_per_px; };
  if (p.present) {
    const double x0 = px(p.strip.start_xy.x()), y0 = py(p.strip.start_xy.y());
    const double x1 = px(p.strip.end_xy.x()), y1 = py(p.strip.end_xy.y());
    for (const auto& [colour, width] : {std::pair<const char*, double>{"#ffffff", 5.0}, {"#111111", 2.2}}) {
      s << "<line x1='" << Fixed(x0, 1) << "' y1='" << Fixed(y0, 1) << "' x2='" << Fixed(x1, 1) << "' y2='"
        << Fixed(y1, 1) << "' stroke='" << colour << "' stroke-width='" << Fixed(width * u, 2) << "'/>";
    }
    for (const auto& [label, x, y] : {std::tuple<const char*, double, double>{"A", x0, y0}, {"B", x1, y1}}) {
      s << "<circle cx='" << Fixed(x, 1) << "' cy='" << Fixed(y, 1) << "' r='" << Fixed(9 * u, 1)
        << "' fill='#111' stroke='#fff' stroke-width='" << Fixed(1.5 * u, 2) << "'/><text x='" << Fixed(x, 1)
        << "' y='" << Fixed(y + 4 * u, 1) << "' text-anchor='middle' fill='#fff' style='font:bold " << Fixed(11 * u, 1)
        << "px DejaVu Sans,Verdana,sans-serif'>" << label << "</text>";
    }
    s << "\n";
  }
  // Scale bar (bottom left) and north arrow (top right), on white plates.
  const double width_m = w * m.metres_per_px;
  const double bar_m = NiceLength(width_m / 4.0);
  const double bar_px = bar_m / m.metres_per_px;
  const double bx = 12 * u, by = h - 14 * u;
  s << "<rect x='" << Fixed(bx - 6 * u, 1) << "' y='" << Fixed(by - 22 * u, 1) << "' width='"
    << Fixed(bar_px + 12 * u, 1) << "' height='" << Fixed(30 * u, 1) << "' fill='#fff' fill-opacity='0.85' rx='"
    << Fixed(3 * u, 1) << "'/>";
  s << "<rect x='" << Fixed(bx, 1) << "' y='" << Fixed(by - 4 * u, 1) << "' width='" << Fixed(bar_px / 2, 1)
    << "' height='" << Fixed(5 * u, 1) << "' fill='#111'/><rect x='" << Fixed(bx + bar_px / 2, 1) << "' y='"
    << Fixed(by - 4 * u, 1) << "' width='" << Fixed(bar_px / 2, 1) << "' height='" << Fixed(5 * u, 1)
    << "' fill='#fff' stroke='#111' stroke-width='" << Fixed(u, 2) << "'/>";
  s << "<text x='" << Fixed(bx + bar_px / 2, 1) << "' y='" << Fixed(by - 8 * u, 1)
    << "' text-anchor='middle' style='font:" << Fixed(12 * u, 1) << "px DejaVu Sans,Verdana,sans-serif'>"
    << TickLabel(bar_m, bar_m) << " m</text>\n";
  const double nx = w - 20 * u, ny = 12 * u;
  s << "<rect x='" << Fixed(nx - 12 * u, 1) << "' y='" << Fixed(ny - 6 * u, 1) << "' width='" << Fixed(24 * u, 1)
    << "' height='" << Fixed(40 * u, 1) << "' fill='#fff' fill-opacity='0.85' rx='" << Fixed(3 * u, 1) << "'/>"
    << "<path d='M" << Fixed(nx, 1) << "," << Fixed(ny, 1) << " l" << Fixed(6 * u, 1) << "," << Fixed(16 * u, 1)
    << " l" << Fixed(-12 * u, 1) << ",0 z' fill='#111'/><text x='" << Fixed(nx, 1) << "' y='" << Fixed(ny + 30 * u, 1)
    << "' text-anchor='middle' style='font:bold " << Fixed(12 * u, 1) << "px DejaVu Sans,Verdana,sans-serif'>N</text>";
  s << "</svg>";
  return s.str();
}

std::string Legend(const ReportData& d, const std::vector<Rgb>& colours) {
  std::vector<ViewKind> kinds;
  for (const ViewCounts& v : d.run.views) kinds.push_back(ClassifyViewName(v.name));
  const bool grouped = ViewKindsKnown(kinds);
  std::ostringstream s;
  s << "<div class='legend'>";
  const auto group = [&](const char* title, ViewKind kind, bool all) {
    size_t n = 0;
    for (size_t i = 0; i < kinds.size(); ++i) n += all || kinds[i] == kind ? 1 : 0;
    if (n == 0) return;
    s << "<div class='grp'>" << title << " (" << n << " views)</div>";
    for (size_t i = 0; i < kinds.size(); ++i) {
      if (!all && kinds[i] != kind) continue;
      const std::string label = grouped ? d.run.views[i].name : "view " + std::to_string(i) + " (ID " + std::to_string(i + 1) + ")";
      s << "<span class='sw' title='" << EscapeHtml(d.run.views[i].name) << ", point source ID " << i + 1
        << "'><i style='background:" << Hex(colours[i]) << "'></i>" << EscapeHtml(label) << "</span>";
    }
  };
  if (grouped) {
    group("Nadir", ViewKind::kNadir, false);
    group("Oblique", ViewKind::kOblique, false);
  } else {
    group("Views", ViewKind::kUnknown, true);
  }
  s << "<div class='grp'>&nbsp;</div><span class='sw'><i style='background:#f6f6f6'></i>no point</span></div>";
  return s.str();
}

std::string MapSection(const ReportData& d, const ReportFigures& f, const std::vector<Rgb>& colours) {
  std::ostringstream s;
  s << "<h2>1. Source views of the fused cloud</h2>\n";
  if (!f.map.present) {
    s << "<p class='note'>No map: " << (d.cloud.exists ? "the cloud has no points." : "there is no " + d.cloud.name + " (yet).")
      << "</p>\n";
    return s.str();
  }
  s << "<p class='caption'>Top view of <code>" << d.cloud.name << "</code>: each " << Fixed(f.map.cell_m, 2)
    << " m cell takes the colour of the view its topmost point came from (LAS point source ID), hill-shaded by that "
       "point's height (light from the north-west). Where a colour forms a patch, one view supplies that surface; "
       "speckle means several views still contribute points there. "
    << GroupedInteger(f.map.points_scanned) << " points in " << GroupedInteger(f.map.cells_filled) << " of "
    << GroupedInteger(f.map.cells_total) << " cells. The line A&ndash;B is the cross-section of section 3.</p>\n";
  s << "<div class='row'><div>" << MapSvg(f.map, f.profile) << "</div>" << Legend(d, colours);
  if (f.dsm.present) {
    s << "<div><h3>DSM</h3>" << MapSvg(f.dsm, f.profile, kDsmDisplayPx)
      << "<p class='caption' style='max-width:" << Fixed(kDsmDisplayPx, 0) << "px'>The run's DSM (<code>dsm.tif</code>, "
         "or <code>dsm.vrt</code> for large blocks), cells of "
      << Fixed(f.dsm.cell_m, 3) << " m, hill-shaded (light from the north-west) over a height tint; grey: no "
         "value.</p></div>";
  }
  if (f.ortho.present) {
    s << "<div><h3>True orthophoto</h3>" << MapSvg(f.ortho, f.profile, kDsmDisplayPx)
      << "<p class='caption' style='max-width:" << Fixed(kDsmDisplayPx, 0) << "px'>The run's true orthophoto "
         "(<code>ortho.tif</code>, or <code>ortho.vrt</code>) on the DSM's cells: each cell resampled from the "
         "original image of the view SAC selected for its surface (the map's colours), or of the most nadir view "
         "that sees it where that one is occluded; light grey: no view sees the cell.</p></div>";
  }
  s << "</div>\n";
  return s.str();
}

// --- 2. Points per view ---------------------------------------------------------------------------------------

std::string HistogramSection(const ReportData& d, const std::vector<Rgb>& colours) {
  std::ostringstream s;
  s << "<h2>2. Points per view, before and after fusion</h2>\n";
  if (d.run.views.empty()) {
    s << "<p class='note'>No per-view counts (run_report.json missing).</p>\n";
    return s.str();
  }
  const size_t half = ViewsForHalfOfPoints(d.run.views);
  s << "<p class='caption'>Per view: valid depth pixels (before, grey) and points of <code>" << d.cloud.name << "</code> with "
       "its source ID (after, in the view's colour), sorted by the after count. "
    << half << " of " << d.run.views.size() << " views supply half of the fused points.</p>\n";
  s << HistogramSvg(d.run.views, colours, 1140, 240) << "\n";
  return s.str();
}

// --- 3. Cross-section --------------------------------------------------------------------------------------

std::string PanelSvg(const std::string& file, const PlotFrame& fr, const std::string& title) {
  std::ostringstream s;
  const double w = std::max(fr.width_px + kPanelAxisLeft + 10, 380.0), h = fr.height_px + kPanelAxisBottom + 22;
  const double ox = kPanelAxisLeft, oy = 22;
  s << "<svg class='chart' width='" << Fixed(w, 0) << "' height='" << Fixed(h, 0)
    << "' viewBox='0 0 " << Fixed(w, 0) << " " << Fixed(h, 0) << "'>"
    << "<text x='" << ox << "' y='15' class='lbl' style='font-weight:bold'>" << EscapeHtml(title) << "</text>"
    << "<image href='" << EscapeHtml(file) << "' x='" << ox << "' y='" << oy << "' width='" << fr.width_px
    << "' height='" << fr.height_px << "'/>"
    << "<rect x='" << ox << "' y='" << oy << "' width='" << fr.width_px << "' height='" << fr.height_px
    << "' fill='none' stroke='#888'/>\n";
  const std::vector<double> zt = NiceTicks(fr.z_min, fr.z_max, 5);
  const double zstep = zt.size() >= 2 ? zt[1] - zt[0] : 1.0;
  for (const double z : zt) {
    const double y = oy + fr.RowOf(z);
    s << "<line x1='" << ox - 4 << "' x2='" << ox << "' y1='" << Fixed(y, 1) << "' y2='" << Fixed(y, 1)
      << "' stroke='#555'/><text x='" << ox - 6 << "' y='" << Fixed(y + 4, 1) << "' text-anchor='end' class='tick'>"
      << TickLabel(z, zstep) << "</text>";
  }
  const std::vector<double> st = NiceTicks(fr.s_min, fr.s_max, 10);
  const double sstep = st.size() >= 2 ? st[1] - st[0] : 1.0;
  for (const double v : st) {
    const double x = ox + fr.ColumnOf(v);
    s << "<line x1='" << Fixed(x, 1) << "' x2='" << Fixed(x, 1) << "' y1='" << oy + fr.height_px << "' y2='"
      << oy + fr.height_px + 4 << "' stroke='#555'/><text x='" << Fixed(x, 1) << "' y='" << oy + fr.height_px + 16
      << "' text-anchor='middle' class='tick'>" << TickLabel(v, sstep) << "</text>";
  }
  s << "<text x='12' y='" << Fixed(oy + fr.height_px / 2.0, 1) << "' class='lbl' transform='rotate(-90 12 "
    << Fixed(oy + fr.height_px / 2.0, 1) << ")' text-anchor='middle'>z (m)</text>"
    << "<text x='" << Fixed(ox + fr.width_px / 2.0, 1) << "' y='" << Fixed(h - 3, 1)
    << "' class='lbl' text-anchor='middle'>distance from A along A&ndash;B (m)</text>";
  s << "<text x='" << ox + 6 << "' y='" << oy + fr.height_px - 6 << "' class='lbl' style='font-weight:bold'>A</text>"
    << "<text x='" << ox + fr.width_px - 6 << "' y='" << oy + fr.height_px - 6
    << "' class='lbl' text-anchor='end' style='font-weight:bold'>B</text>";
  s << "</svg>";
  return s.str();
}

std::string ProfileSection(const ReportData& d, const ReportFigures& f) {
  std::ostringstream s;
  const ProfileFigure& p = f.profile;
  s << "<h2>3. Cross-section through a building, before and after fusion</h2>\n";
  if (!p.present) {
    s << "<p class='note'>No cross-section: " << EscapeHtml(p.reason) << "</p>\n";
    return s.str();
  }
  const ProfileStrip& st = p.strip;
  const bool along_x = std::abs(st.end_xy.x() - st.start_xy.x()) >= std::abs(st.end_xy.y() - st.start_xy.y());
  s << "<p class='caption'>A " << Fixed(2 * st.half_width_m, 2) << " m wide (2 GSD; GSD " << Fixed(p.gsd_m, 3)
    << " m from the " << EscapeHtml(p.gsd_source) << ") and " << Fixed(st.Length(), 1) << " m long strip from A ("
    << Fixed(st.start_xy.x(), 1) << ", " << Fixed(st.start_xy.y(), 1) << ") to B (" << Fixed(st.end_xy.x(), 1) << ", "
    << Fixed(st.end_xy.y(), 1) << "), running " << (along_x ? "west&ndash;east" : "south&ndash;north")
    << ", picked automatically: through the smooth roof cell highest above its local ground (" << Fixed(st.relief_m, 1)
    << " m above the lowest top within 15 m)" << (p.has_reference ? " inside the reference's extent" : "")
    << ", away from the block's border, across the building the short way, with ground on both sides. "
       "Points are shown as distance along the strip vs height, coloured by source view as on the map";
  if (p.has_reference) s << "; black: the reference point cloud";
  s << ". Vertical exaggeration " << Fixed(p.frame.VerticalExaggeration(), 2) << "&times;.</p>\n";
  s << "<div class='row'>";
  if (!p.before_file.empty()) {
    s << "<div>"
      << PanelSvg(p.before_file, p.frame,
                  "Before: " + std::to_string(p.before_views) + " views, " + GroupedInteger(p.before_in_strip) +
                      " points" +
                      (p.before_drawn < p.before_in_strip ? " (" + GroupedInteger(p.before_drawn) + " drawn)" : ""))
      << "</div>";
  }
  s << "<div>"
    << PanelSvg(p.after_file, p.frame,
                "After: " + d.cloud.name + ", " + GroupedInteger(p.after_in_strip) + " points" +
                    (p.after_drawn < p.after_in_strip ? " (" + GroupedInteger(p.after_drawn) + " drawn)" : ""))
    << "</div></div>\n";
  s << "<p class='caption'>Before: every valid depth pixel of the views that see the strip, back-projected; after: "
       "the points of <code>" + d.cloud.name + "</code>"
    << (p.after_source != d.cloud.name ? " (read from the " + EscapeHtml(p.after_source) + " under the strip)" : "")
    << ". ";
  if (p.has_reference) {
    s << "Reference: " << GroupedInteger(p.reference_in_strip) << " points of <code>" << EscapeHtml(d.reference_path)
      << "</code> in the strip. ";
  } else {
    s << "No reference configured (<code>evaluation.reference</code>). ";
  }
  if (p.before_file.empty()) {
    s << "No 'before' panel"
      << (p.before_reason.empty() ? " (the input's depth maps were not read)" : ": " + EscapeHtml(p.before_reason))
      << ". ";
  }
  if (!p.before_file.empty()) {
    s << GroupedInteger(p.before_window_pixels) << " depth pixels read from the windows covering the strip. ";
  }
  s << "Points outside the plotted height range are not drawn.</p>\n";
  return s.str();
}

// --- 4. Tiles ---------------------------------------------------------------------------------------------

std::string TilesSection(const ReportData& d) {
  std::ostringstream s;
  s << "<h2>4. Tiles</h2>\n";
  if (!d.tiled) {
    Box2d extent;
    if (d.cloud.exists && d.cloud.points > 0) {
      extent.Extend(Eigen::Vector2d(d.cloud.min[0], d.cloud.min[1]));
      extent.Extend(Eigen::Vector2d(d.cloud.max[0], d.cloud.max[1]));
    }
    s << "<p class='caption'>Untiled run";
    if (!d.run.tiling_reason.empty()) s << " (" << EscapeHtml(d.run.tiling_reason) << ")";
    s << ": the whole block was fused at once. Its extent:</p>\n" << UntiledExtentSvg(extent, 300, 200) << "\n";
    return s.str();
  }
  size_t done = 0, failed = 0, pending = 0;
  double total_s = 0, max_s = 0, max_rss = 0;
  for (const ReportTile& t : d.tiles) {
    done += t.status == TileStatus::kDone;
    failed += t.status == TileStatus::kFailed;
    pending += t.status == TileStatus::kPending;
    if (t.status == TileStatus::kDone) {
      total_s += t.seconds;
      max_s = std::max(max_s, t.seconds);
      max_rss = std::max(max_rss, t.peak_rss_mib);
    }
  }
  s << "<p class='caption'>" << d.tiles.size() << " tiles of " << TickLabel(d.tile_size_m, 0.1) << " m with views: "
    << done << " done, " << failed << " failed, " << pending << " pending (from the markers in <code>tiles/</code>). "
    << "Tile time: " << Duration(total_s) << " in total, " << Duration(max_s) << " the slowest; process peak RSS when "
    << "a tile finished: up to " << Fixed(max_rss, 0) << " MiB. Hover a tile for its numbers.</p>\n";
  s << "<div class='row'><div><h3>Status</h3>" << TileMapSvg(d.tiles, TileColouring::kStatus, 560, 520)
    << "</div><div><h3>Wall time per tile</h3>" << TileMapSvg(d.tiles, TileColouring::kTime, 560, 520)
    << "</div></div>\n";
  s << "<details><summary>Per-tile table</summary><table><tr><th>tile</th><th>status</th><th class='n'>points</th>"
       "<th class='n'>views</th><th class='n'>time</th><th class='n'>peak RSS MiB</th>"
       "<th class='n'>estimate MiB</th><th>note</th></tr>";
  for (const ReportTile& t : d.tiles) {
    s << "<tr><td>" << EscapeHtml(t.id) << "</td><td>" << TileStatusName(t.status) << "</td><td class='n'>"
      << (t.status == TileStatus::kDone ? GroupedInteger(t.points) : "") << "</td><td class='n'>"
      << (t.status == TileStatus::kDone ? std::to_string(t.views) : "") << "</td><td class='n'>"
      << (t.status == TileStatus::kDone ? Duration(t.seconds) : "") << "</td><td class='n'>"
      << (t.status == TileStatus::kDone ? Fixed(t.peak_rss_mib, 0) : "") << "</td><td class='n'>"
      << (t.memory_estimate_bytes ? Fixed(t.memory_estimate_bytes / 1048576.0, 0) : "") << "</td><td>"
      << EscapeHtml(t.reason) << "</td></tr>";
  }
  s << "</table></details>\n";
  return s.str();
}

// --- 5. Numbers ---------------------------------------------------------------------------------------------

std::string Row(const std::string& key, const std::string& value) {
  return "<tr><td>" + key + "</td><td class='n'>" + value + "</td></tr>";
}

std::string NumbersSection(const ReportData& d, const ReportFigures& f) {
  std::ostringstream s;
  s << "<h2>5. Numbers</h2>\n<div class='tables'>";
  const ReportRun& r = d.run;
  const uint64_t in = PointsIn(d), out = PointsOut(d);
  s << "<div><h3>Run</h3><table>";
  s << Row("method", EscapeHtml(r.method));
  s << Row("points in (valid depth pixels)", GroupedInteger(in));
  s << Row("points out", GroupedInteger(out));
  if (in > 0) s << Row("redundancy removed (1 &minus; out/in)", Percent(RedundancyRemoved(in, out), 2));
  s << Row("views", std::to_string(r.views.size()));
  if (r.present) {
    s << Row("wall time", Duration(r.wall_seconds) + (r.wall_seconds >= 60 ? " (" + Fixed(r.wall_seconds, 0) + " s)" : ""));
    s << Row("CPU time", Fixed(r.cpu_seconds, 1) + " s");
    s << Row("peak RSS", Fixed(r.peak_rss_mib, 0) + " MiB");
    s << Row("threads", std::to_string(r.threads));
    s << Row("memory budget", Fixed(r.memory_budget_gib, 2) + " GiB");
    s << Row(r.tile_size_m > 0 ? "memory estimate (largest tile)" : "memory estimate (whole block)",
             Fixed(r.memory_estimate_gib * 1024.0, 0) + " MiB");
    s << Row("tiling", r.tile_size_m > 0 ? TickLabel(r.tile_size_m, 0.1) + " m tiles" : "untiled");
    if (r.superpixel_seconds > 0) s << Row("superpixels stage", Fixed(r.superpixel_seconds, 1) + " s");
    if (r.tiles_seconds > 0) s << Row("tiles stage", Fixed(r.tiles_seconds, 1) + " s");
    if (r.merge_seconds > 0) s << Row("merge stage", Fixed(r.merge_seconds, 1) + " s");
  }
  s << "</table></div>";
  if (r.has_sac) {
    s << "<div><h3>SAC</h3><table>";
    s << Row("superpixel nodes", GroupedInteger(r.sac_nodes));
    s << Row("Netlets", GroupedInteger(r.sac_netlets));
    s << Row("nodes relabelled", GroupedInteger(r.sac_nodes_relabelled));
    s << Row("pixels collapsed", GroupedInteger(r.sac_pixels_collapsed));
    s << Row("pixels kept (uncovered)", GroupedInteger(r.sac_pixels_kept_uncovered));
    s << Row("pixels removed as outliers", GroupedInteger(r.sac_pixels_outliers));
    s << "</table><div class='sub'>Computed by the last invocation (tiles skipped on resume are not counted).</div>"
         "</div>";
  }
  s << "<div><h3>Accuracy against the reference</h3>";
  if (d.eval.present) {
    s << "<table><tr><th class='n'>&tau; (m)</th><th class='n'>accuracy</th><th class='n'>completeness</th>"
         "<th class='n'>F1</th></tr>";
    for (const ReportEvalScore& e : d.eval.scores) {
      s << "<tr><td class='n'>" << TickLabel(e.tau_m, 0.01) << "</td><td class='n'>" << Percent(e.accuracy, 2)
        << "</td><td class='n'>" << Percent(e.completeness, 2) << "</td><td class='n'><b>" << Percent(e.f1, 2)
        << "</b></td></tr>";
    }
    s << "</table><table>" << Row("mean / median |distance|", Fixed(d.eval.mean_abs_distance_m, 3) + " / " +
                                                                  Fixed(d.eval.median_abs_distance_m, 3) + " m")
      << Row("points scored (result / reference)", GroupedInteger(d.eval.result_points_evaluated) + " / " +
                                                       GroupedInteger(d.eval.reference_points_evaluated))
      << (d.eval.result_stride > 1 ? Row("result subsampled", "every " + std::to_string(d.eval.result_stride) + "th point")
                                   : "")
      << (d.eval.aligned ? Row("aligned", "robust ICP before scoring") : "") << "</table>"
      << "<div class='sub'>Density-normalised (per-voxel) scores of <code>eval.json</code>; see docs/evaluation.md.</div>";
  } else if (d.eval.stale) {
    s << "<p class='note'>eval.json is older than " << d.cloud.name << ", so its scores describe an earlier cloud and are not "
         "shown; <code>sacfuse run</code> rescores (or run <code>sacfuse eval</code>, then <code>sacfuse report</code>).</p>";
  } else if (!d.reference_path.empty()) {
    s << "<p class='note'>Not scored yet (<code>eval.json</code> missing): the run scores after fusion and then "
         "rewrites this page.</p>";
  } else {
    s << "<p class='note'>No reference configured (<code>evaluation.reference</code>).</p>";
  }
  s << "</div></div>\n";
  if (f.seconds > 0) {
    s << "<p class='sub'>This report's pictures took " << Fixed(f.seconds, 1) << " s (process peak RSS "
      << Fixed(f.peak_rss_mib, 0) << " MiB).</p>\n";
  }
  return s.str();
}

std::string ConfigSection(const ReportData& d) {
  std::ostringstream s;
  s << "<h2>6. Configuration used</h2>\n";
  if (d.effective_config.empty()) {
    s << "<p class='note'>sacfuse.effective.yaml not found.</p>\n";
    return s.str();
  }
  s << "<details><summary><code>sacfuse.effective.yaml</code> (defaults filled in)</summary><pre>"
    << EscapeHtml(d.effective_config) << "</pre></details>\n";
  return s.str();
}

}  // namespace

double RedundancyRemoved(uint64_t points_in, uint64_t points_out) {
  return points_in > 0 ? 1.0 - static_cast<double>(points_out) / static_cast<double>(points_in) : 0.0;
}

std::vector<Rgb> ReportViewColours(const ReportData& data) {
  std::vector<ViewKind> kinds;
  for (const ViewCounts& v : data.run.views) kinds.push_back(ClassifyViewName(v.name));
  return ViewColours(kinds);
}

std::string RenderReportPage(const ReportData& d, const ReportFigures& f) {
  const std::vector<Rgb> colours = ReportViewColours(d);
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>sacfuse report: "
    << EscapeHtml(d.output_dir) << "</title><style>" << kCss << "</style></head><body><main>\n";
  s << Header(d) << Warnings(d) << Summary(d);
  s << MapSection(d, f, colours) << HistogramSection(d, colours) << ProfileSection(d, f) << TilesSection(d)
    << NumbersSection(d, f) << ConfigSection(d);
  s << "</main></body></html>\n";
  return s.str();
}

}  // namespace sacfuse
