#pragma once
// Points per view before and after fusion (the paper's Fig. 4) as an SVG bar chart: per view a light bar for the
// valid depth pixels (before) and a bar in the view's colour for the points written with its source ID (after),
// views sorted by the after count (descending; ties by view index). Pure: counts in, SVG text out.
#include <cstdint>
#include <string>
#include <vector>

#include "report/report_colours.h"

namespace sacfuse {

struct ViewCounts {
  uint32_t view = 0;     // view index
  std::string name;
  uint64_t before = 0;   // valid depth pixels
  uint64_t after = 0;    // fused points with this view as source
};

struct HistogramBar {
  uint32_t view = 0;
  double x = 0.0;              // left edge of the view's slot, SVG px
  double before_height = 0.0;  // px; bar height proportional to the count (max count = plot height)
  double after_height = 0.0;
};

struct HistogramLayout {
  double width = 0.0, height = 0.0;         // whole SVG, px
  double plot_left = 0.0, plot_top = 0.0;   // the plot area (bars stand on plot_top + plot_height)
  double plot_width = 0.0, plot_height = 0.0;
  double slot = 0.0;                        // px per view
  double max_count = 0.0;                   // the count at plot_height (a "nice" value >= every count)
  std::vector<HistogramBar> bars;           // sorted as described above
  std::vector<double> ticks;                // count values of the y-axis ticks
};

// Sorted by after count, descending (stable on view index).
std::vector<ViewCounts> SortedByAfter(std::vector<ViewCounts> counts);

// Layout for an SVG of `width_px` and plot height `plot_height_px` (labels below it take more).
HistogramLayout LayoutHistogram(const std::vector<ViewCounts>& counts, double width_px, double plot_height_px);

// The chart (a complete <svg> element). Views' names label the slots when they fit, else view ids.
std::string HistogramSvg(const std::vector<ViewCounts>& counts, const std::vector<Rgb>& colours_by_view,
                         double width_px, double plot_height_px);

// How many views (largest first) supply half of the after points.
size_t ViewsForHalfOfPoints(const std::vector<ViewCounts>& counts);

}  // namespace sacfuse
