#pragma once
// What the report's pictures show, recorded next to them in report/figures.json so the page can be rewritten
// without recomputing them (after scoring adds eval.json): the map's georeference and the cross-section's strip,
// frame and point counts.
#include <cstdint>
#include <string>
#include <vector>

#include "report/report_profile.h"
#include "report/report_profile_figure.h"

namespace sacfuse {

struct MapFigure {
  bool present = false;
  std::string file;             // PNG, relative to the report folder
  int width_px = 0, height_px = 0;
  double x_min = 0.0, y_max = 0.0;  // world XY of the picture's top-left corner, metres
  double metres_per_px = 1.0;
  double cell_m = 1.0;              // top-grid cell
  uint64_t points_scanned = 0;      // points of fused.las streamed into the grid
  uint64_t cells_filled = 0, cells_total = 0;
};

struct ProfileFigure {
  bool present = false;
  std::string reason;           // why absent
  std::string before_file, after_file;  // PNGs ("" when that panel is absent)
  ProfileStrip strip;
  PlotFrame frame;              // both panels
  double gsd_m = 0.0;           // strip width is 2 GSD
  std::string gsd_source;       // "views" (depth of the views at the strip) | "cloud spacing"
  uint64_t before_in_strip = 0, after_in_strip = 0, reference_in_strip = 0;  // points inside the strip
  uint64_t before_drawn = 0, after_drawn = 0, reference_drawn = 0;           // sampled and drawn
  std::string before_reason;    // why the "before" panel is absent ("" when present or not asked for)
  size_t before_views = 0;      // views whose depth window covers the strip
  uint64_t before_window_pixels = 0;
  bool has_reference = false;
  std::string after_source;     // "fused.las" or "N tile files"
};

struct ReportFigures {
  MapFigure map;
  MapFigure dsm;                // the DSM's hill-shade thumbnail (output.dsm), points_scanned/cells_filled unused
  MapFigure ortho;              // the true orthophoto's thumbnail (output.ortho), likewise
  ProfileFigure profile;
  double seconds = 0.0;         // time to make the figures
  double map_seconds = 0.0;     // of which streaming fused.las into the map
  double profile_seconds = 0.0; // and the cross-section (strip, LAS files, depth windows)
  double peak_rss_mib = 0.0;    // process peak RSS after making them
};

std::string ReportFiguresToJson(const ReportFigures& figures);
// Throws std::exception on malformed text.
ReportFigures ReportFiguresFromJson(const std::string& text);

}  // namespace sacfuse
