#pragma once
// The fused cloud seen from above at a bounded resolution, for the run report: per XY cell the height and the
// point source ID of its topmost point (the paper's Fig. 3), and how many points fell in it. Memory is fixed by
// the cell count (10 bytes per cell), whatever the number of points streamed through Add.
//
// Layout: cell (row, col) covers x in [x_min + col * cell_m, x_min + (col + 1) * cell_m) and
// y in (y_max - (row + 1) * cell_m, y_max - row * cell_m], so row 0 is the northern edge (image order: north up).
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "io/las_types.h"

namespace sacfuse {

struct TopGrid {
  double x_min = 0.0;   // world x of the western edge, metres
  double y_max = 0.0;   // world y of the northern edge, metres
  double cell_m = 1.0;  // cell edge, metres
  int width = 0;        // cells along x
  int height = 0;       // cells along y
  std::vector<float> top_z;          // world z of the topmost point, metres; NaN = empty cell
  std::vector<uint16_t> source_id;   // LAS point source ID of that point (view index + 1); 0 = empty
  std::vector<uint32_t> count;       // points in the cell (saturating)

  // An empty grid of width x height cells.
  TopGrid(double x_min_m, double y_max_m, double cell_size_m, int width_cells, int height_cells);
  TopGrid() = default;

  size_t num_cells() const { return static_cast<size_t>(width) * height; }
  size_t Index(int row, int col) const { return static_cast<size_t>(row) * width + col; }
  bool Empty(int row, int col) const { return std::isnan(top_z[Index(row, col)]); }
  // The cell holding (x, y), or nullopt outside the grid.
  std::optional<size_t> CellOf(double x, double y) const;
  // World XY of a cell's centre.
  double CellCenterX(int col) const { return x_min + (col + 0.5) * cell_m; }
  double CellCenterY(int row) const { return y_max - (row + 0.5) * cell_m; }

  // Adds one point; a point higher than the cell's top replaces it (ties keep the first). Points outside the
  // grid are ignored (returns false).
  bool Add(double x, double y, double z, uint16_t point_source_id);
  // Adds one point to cell `i` (< num_cells()), as Add does.
  void AddToCell(size_t i, double z, uint16_t point_source_id);
};

// Adds streamed points to a grid on the calling task arena's threads: the grid's rows in `bands` bands, each band
// filled by one task from the points that fall in it, in their order, so every cell sees its points in the
// stream's order and the grid is the same as adding them one by one with TopGrid::Add, for any number of bands
// and threads. Each block of 4,096 points is sorted into the bands once (a list of point indices per block and
// band), so the work does not grow with the number of bands. Holds a cell index per point of the largest batch
// added and the bands' index lists (4 bytes a point).
class TopGridFiller {
 public:
  // `grid` must outlive the filler; `bands` >= 1 (more than the grid's rows are as many as its rows).
  TopGridFiller(TopGrid* grid, size_t bands);
  void Add(const std::vector<LasPoint>& points);

 private:
  TopGrid* grid_;
  size_t bands_;
  std::vector<uint32_t> band_of_row_;
  std::vector<size_t> cells_;                  // per point of the batch: its cell
  std::vector<std::vector<uint32_t>> in_band_;  // [block * bands + band]: the block's points in the band, in order
};

// Cell size for a cloud of `points` over the XY box [min_x, max_x] x [min_y, max_y]: at least 2.5 x the mean point
// spacing (so most cells get a point although points crowd on some surfaces and thin out on others), at least min_cell_m, and coarse enough that neither side exceeds max_cells.
double TopGridCellSize(double extent_x_m, double extent_y_m, uint64_t points, int max_cells, double min_cell_m);

// A grid covering the box with cells of TopGridCellSize.
TopGrid MakeTopGrid(double min_x, double min_y, double max_x, double max_y, uint64_t points, int max_cells,
                    double min_cell_m);

}  // namespace sacfuse
