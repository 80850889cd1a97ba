#pragma once
// The cross-section panels of the run report: points as distance along the strip (x) vs height (z), coloured by
// their view, with the reference on top in black. Pure: points in, RGB out. Axes and labels are drawn by the
// page (SVG around the picture), from the same PlotFrame.
#include <vector>

#include "core/raster.h"
#include "report/report_colours.h"
#include "report/report_profile.h"

namespace sacfuse {

// The data window of a panel and its size in pixels: along_m in [s_min, s_max] maps to columns [0, width_px),
// z in [z_min, z_max] to rows (height_px, 0] (up is up).
struct PlotFrame {
  double s_min = 0.0, s_max = 1.0;
  double z_min = 0.0, z_max = 1.0;
  int width_px = 1000, height_px = 300;

  double ColumnOf(double s) const { return (s - s_min) / (s_max - s_min) * width_px; }
  double RowOf(double z) const { return (z_max - z) / (z_max - z_min) * height_px; }
  // Pixels per metre vertically over pixels per metre horizontally (1 = true shape).
  double VerticalExaggeration() const {
    return (height_px / (z_max - z_min)) / (width_px / (s_max - s_min));
  }
};

// A frame for a strip of `length_m` and heights [z_min, z_max], true shape (exaggeration 1) when possible: at
// max_width_px when the height that gives is within [min_height_px, max_height_px]; a taller section gets
// max_height_px and a narrower width (down to min_width_px, below which it is squashed); a flatter one gets
// min_height_px (exaggerated).
PlotFrame MakePlotFrame(double length_m, double z_min, double z_max, int max_width_px, int min_width_px,
                        int min_height_px, int max_height_px);

// Height range to plot: the 0.5 .. 99.5 percentile of the given points' z (so a few blunders do not squash the
// picture), padded by 5 % (at least 1 m). *lo/*hi unchanged when there are no points.
void RobustHeightRange(const std::vector<const std::vector<ProfilePoint>*>& sets, double* lo, double* hi);

struct ProfileStyle {
  int dot_px = 2;                  // side of a point's square
  double alpha = 0.55;             // opacity of view points
  int reference_dot_px = 3;
  Rgb background = {255, 255, 255};
  Rgb reference = {0, 0, 0};
  Rgb grid = {232, 232, 232};      // horizontal lines at `grid_z`
};

// The panel: `points` (coloured by source ID via colours_by_view), then `reference` (may be empty) on top;
// points outside the frame are not drawn. Light horizontal grid lines at the heights in grid_z.
RgbImage RenderProfilePanel(const std::vector<ProfilePoint>& points, const std::vector<ProfilePoint>& reference,
                            const std::vector<Rgb>& colours_by_view, const PlotFrame& frame,
                            const std::vector<double>& grid_z, const ProfileStyle& style = {});

}  // namespace sacfuse
