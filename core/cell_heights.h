#pragma once
// Heights of the points falling in each cell of a window (core/cell_window.h), reduced to one value per cell:
// the q-quantile of the cell's z (the element at position min(n - 1, floor(q (n - 1) + 0.5)) of the n sorted z
// values, as ../shared/aerial-bench/score_dsm.py grids clouds), or no value (NaN) for a cell with fewer than
// min_points points. q = 1 is the highest point. Memory: 8 bytes per point added, so callers give it the
// points of one tile or one band of a cloud, never an unbounded stream.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "core/cell_window.h"
#include "core/default_init_allocator.h"

namespace sacfuse {

constexpr float kNoCellValue = std::numeric_limits<float>::quiet_NaN();

// The value of one cell from the z of all its points (the rule Reduce applies to every cell): the q-quantile as
// above, kNoCellValue below min_points. Sorts *z (float z, as CellHeights keeps them).
float CellValueOf(std::vector<float>* z, double quantile, int min_points);

class CellHeights {
 public:
  explicit CellHeights(const CellWindow& window);

  // The window's cell holding (x, y); false when none does.
  bool CellOf(double x, double y, int64_t* col, int64_t* row) const;
  // z is kept as float (the raster's type). Add ignores points outside the window (counted in ignored()).
  void Add(double x, double y, double z);
  void AddToCell(int64_t col, int64_t row, double z);  // (col, row) must lie in the window
  // The cell (inside the window) and z of point i of a batch; false leaves the point out.
  using PointCell = std::function<bool(size_t i, int64_t* col, int64_t* row, double* z)>;
  // AddToCell of every point i in [0, count) that point_cell places, on the job's threads (point_cell is called
  // concurrently). The values Reduce gives do not depend on the order in which points were added.
  void AddInParallel(size_t count, const PointCell& point_cell);
  // Room for `points` points in all (8 bytes each), so that adding them does not grow and copy the keys on one
  // thread as they come.
  void Reserve(uint64_t points) { keys_.reserve(static_cast<size_t>(points)); }
  uint64_t points() const { return keys_.size(); }
  uint64_t ignored() const { return ignored_; }
  const CellWindow& window() const { return window_; }

  // One value per cell of the window, north-up (CellWindow::Index); consumes the points. Sorts on the job's
  // threads.
  std::vector<float> Reduce(double quantile, int min_points);

 private:
  CellWindow window_;
  // (raster index << 32) | order-preserving bits of the float z; grown without a zero fill (AddInParallel writes
  // every new key on the job's threads).
  std::vector<uint64_t, DefaultInitAllocator<uint64_t>> keys_;
  uint64_t ignored_ = 0;
};

}  // namespace sacfuse
