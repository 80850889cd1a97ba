#pragma once
// The source-view map of the run report (the paper's Fig. 3): each cell of the top grid coloured by the view its
// topmost point came from, lightly hill-shaded by the top height so buildings read. Pure: grid in, RGB out.
#include <vector>

#include "core/raster.h"
#include "report/report_colours.h"
#include "report/report_top_grid.h"

namespace sacfuse {

struct SourceMapStyle {
  int pixels_per_cell = 1;          // nearest-neighbour enlargement of each cell
  double shade_strength = 0.55;     // 0 = flat colours; a flat surface keeps its colour at any strength
  double sun_azimuth_deg = 315.0;   // light from the north-west (clockwise from north)
  double sun_elevation_deg = 45.0;
  Rgb empty = {246, 246, 246};      // cells without points
};

// Hill-shade factor of each cell of a height raster (`z`: width x height, row 0 north, NaN = empty, cells of
// cell_m): 1 on flat ground, above 1 facing the sun, below facing away, in [0.35, 1.45]; 1 for empty cells.
// Gradients by central differences (one-sided next to empty cells).
std::vector<float> HillShade(const std::vector<float>& z, int width, int height, double cell_m,
                             const SourceMapStyle& style);
// The same for the top grid's heights.
std::vector<float> HillShade(const TopGrid& grid, const SourceMapStyle& style);

// The DSM thumbnail: a height raster (as HillShade's) hill-shaded over a hypsometric tint (green low, sand, white
// high, stretched over the 2nd..98th percentile of its heights), empty cells in style.empty; one pixel per cell.
RgbImage RenderDsmHillShade(const std::vector<float>& z, int width, int height, double cell_m,
                            const SourceMapStyle& style);

// The map: grid.width x grid.height cells, each pixels_per_cell^2 pixels; colour = colours_by_view[source_id - 1]
// (kUnknownViewColour for IDs beyond it) times the hill-shade factor.
RgbImage RenderSourceMap(const TopGrid& grid, const std::vector<Rgb>& colours_by_view, const SourceMapStyle& style);

// The enlargement that makes the longer side of the grid at most `target_px` pixels (at least 1).
int PixelsPerCellFor(const TopGrid& grid, int target_px);

}  // namespace sacfuse
