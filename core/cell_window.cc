#include "core/cell_window.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sacfuse {
namespace {

int64_t FloorDiv(int64_t a, int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0); }

}  // namespace

CellWindow CellWindow::Grown(int64_t cells) const {
  CellWindow w = *this;
  w.col0 -= cells;
  w.row0 -= cells;
  w.cols += 2 * cells;
  w.rows += 2 * cells;
  return w;
}

CellWindow CellWindow::Intersection(const CellWindow& o) const {
  CellWindow w;
  w.cell_m = cell_m;
  w.col0 = std::max(col0, o.col0);
  w.row0 = std::max(row0, o.row0);
  w.cols = std::max<int64_t>(0, std::min(col0 + cols, o.col0 + o.cols) - w.col0);
  w.rows = std::max<int64_t>(0, std::min(row0 + rows, o.row0 + o.rows) - w.row0);
  if (w.cols == 0 || w.rows == 0) w.cols = w.rows = 0;
  return w;
}

CellWindow CellWindowCovering(const Box2d& box, double cell_m) {
  CellWindow w;
  w.cell_m = cell_m;
  if (box.IsEmpty()) return w;
  w.col0 = CellIndexOf(box.min.x(), cell_m);
  w.row0 = CellIndexOf(box.min.y(), cell_m);
  w.cols = CellIndexOf(box.max.x(), cell_m) - w.col0 + 1;
  w.rows = CellIndexOf(box.max.y(), cell_m) - w.row0 + 1;
  return w;
}

CellWindow CellWindowOfHalfOpen(const Box2d& box, double cell_m) {
  CellWindow w;
  w.cell_m = cell_m;
  if (!box.HasArea()) return w;
  // The first cell whose west edge is at or beyond the box's max edge ends the window.
  const auto end = [&](double v) {
    const int64_t k = CellIndexOf(v, cell_m);
    return CellEdge(k, cell_m) >= v ? k : k + 1;
  };
  w.col0 = CellIndexOf(box.min.x(), cell_m);
  w.row0 = CellIndexOf(box.min.y(), cell_m);
  w.cols = end(box.max.x()) - w.col0;
  w.rows = end(box.max.y()) - w.row0;
  return w;
}

bool IsWholeNumberOfCells(double size_m, double cell_m) {
  if (!(cell_m > 0) || !(size_m > 0)) return false;
  const double n = size_m / cell_m;
  return std::abs(n - std::round(n)) <= 1e-9 * std::max(1.0, n);
}

std::vector<CellBlock> CellBlocksOf(const CellWindow& extent, int64_t block_cells) {
  std::vector<CellBlock> blocks;
  if (extent.empty() || block_cells <= 0) return blocks;
  const int64_t bx0 = FloorDiv(extent.col0, block_cells), bx1 = FloorDiv(extent.col0 + extent.cols - 1, block_cells);
  const int64_t by0 = FloorDiv(extent.row0, block_cells), by1 = FloorDiv(extent.row0 + extent.rows - 1, block_cells);
  for (int64_t by = by1; by >= by0; --by) {  // north first
    for (int64_t bx = bx0; bx <= bx1; ++bx) {
      CellWindow b;
      b.cell_m = extent.cell_m;
      b.col0 = bx * block_cells;
      b.row0 = by * block_cells;
      b.cols = b.rows = block_cells;
      blocks.push_back({bx, by, b.Intersection(extent)});
    }
  }
  return blocks;
}

}  // namespace sacfuse
