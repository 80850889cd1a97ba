#pragma once
// The cells of a raster product (the DSM, and later the true orthophoto): square cells of edge cell_m whose edges
// lie at integer multiples of cell_m in the project CRS, so every raster of one cell size shares one lattice and
// tiles, blocks and whole-block rasters line up cell for cell. Column c covers x in [c * cell_m, (c + 1) * cell_m),
// row r covers y in [r * cell_m, (r + 1) * cell_m) (global indices, rows counted north). A CellWindow is a
// rectangle of that lattice; its raster is stored north-up (raster row 0 = the northern row), as GeoTIFF wants.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/box2d.h"

namespace sacfuse {

inline double CellEdge(int64_t k, double cell_m) { return static_cast<double>(k) * cell_m; }
// The column (or row) holding coordinate v (finite): the k with Edge(k) <= v < Edge(k + 1), Edge(k) = k * cell_m
// computed in double, the one formula for cell edges. Inline, without floor's library call: the DSM and the true
// ortho ask it twice per point. The truncated quotient is a guess at most a cell or two off; the edges decide.
inline int64_t CellIndexOf(double v, double cell_m) {
  int64_t k = static_cast<int64_t>(v / cell_m);
  while (CellEdge(k, cell_m) > v) --k;
  while (CellEdge(k + 1, cell_m) <= v) ++k;
  return k;
}

struct CellWindow {
  double cell_m = 1.0;
  int64_t col0 = 0, row0 = 0;  // global index of the western column and the southern row
  int64_t cols = 0, rows = 0;

  bool empty() const { return cols <= 0 || rows <= 0; }
  size_t size() const { return empty() ? 0 : static_cast<size_t>(cols) * static_cast<size_t>(rows); }
  double west() const { return CellEdge(col0, cell_m); }
  double east() const { return CellEdge(col0 + cols, cell_m); }
  double south() const { return CellEdge(row0, cell_m); }
  double north() const { return CellEdge(row0 + rows, cell_m); }
  bool Contains(int64_t col, int64_t row) const {
    return col >= col0 && col < col0 + cols && row >= row0 && row < row0 + rows;
  }
  // Position of global cell (col, row) in the north-up raster of the window (Contains must hold).
  size_t Index(int64_t col, int64_t row) const {
    return static_cast<size_t>(row0 + rows - 1 - row) * static_cast<size_t>(cols) + static_cast<size_t>(col - col0);
  }
  // Raster offset (x = column, y = row from the north) of this window inside `outer`, which must contain it.
  int64_t XOffsetIn(const CellWindow& outer) const { return col0 - outer.col0; }
  int64_t YOffsetIn(const CellWindow& outer) const { return (outer.row0 + outer.rows) - (row0 + rows); }
  // The window grown by `cells` on every side.
  CellWindow Grown(int64_t cells) const;
  // The common cells (empty() when none).
  CellWindow Intersection(const CellWindow& other) const;
  bool operator==(const CellWindow& o) const {
    return cell_m == o.cell_m && col0 == o.col0 && row0 == o.row0 && cols == o.cols && rows == o.rows;
  }
  bool operator!=(const CellWindow& o) const { return !(*this == o); }
};

// The cells meeting the closed box (a point on its max edge included): the extent of a product over an area.
CellWindow CellWindowCovering(const Box2d& box, double cell_m);
// The cells of a half-open box [min, max) whose edges lie on the lattice (a tile core when the tile size is a
// multiple of the cell): exactly the cells whose points the box owns.
CellWindow CellWindowOfHalfOpen(const Box2d& box, double cell_m);
// Whether `size_m` is a whole number of cells (within 1e-9 of one), e.g. a tile edge that tiles the lattice.
bool IsWholeNumberOfCells(double size_m, double cell_m);

// Blocks of at most block_cells x block_cells cells covering `extent`, aligned to multiples of block_cells in the
// global lattice (so the blocks of two extents of one cell size coincide where they overlap), row by row from the
// north-west; each clipped to the extent.
struct CellBlock {
  int64_t bx = 0, by = 0;  // global block indices (floor(col / block_cells), floor(row / block_cells))
  CellWindow window;
};
std::vector<CellBlock> CellBlocksOf(const CellWindow& extent, int64_t block_cells);

}  // namespace sacfuse
