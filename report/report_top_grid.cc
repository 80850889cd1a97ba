#include "report/report_top_grid.h"

#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>

namespace sacfuse {

TopGrid::TopGrid(double x_min_m, double y_max_m, double cell_size_m, int width_cells, int height_cells)
    : x_min(x_min_m),
      y_max(y_max_m),
      cell_m(cell_size_m),
      width(width_cells),
      height(height_cells),
      top_z(static_cast<size_t>(width_cells) * height_cells, std::numeric_limits<float>::quiet_NaN()),
      source_id(static_cast<size_t>(width_cells) * height_cells, 0),
      count(static_cast<size_t>(width_cells) * height_cells, 0) {}

std::optional<size_t> TopGrid::CellOf(double x, double y) const {
  const double fc = (x - x_min) / cell_m;
  const double fr = (y_max - y) / cell_m;
  if (!(fc >= 0.0) || !(fr >= 0.0)) return std::nullopt;  // also rejects NaN
  const auto col = static_cast<long long>(fc);
  const auto row = static_cast<long long>(fr);
  if (col >= width || row >= height) return std::nullopt;
  return Index(static_cast<int>(row), static_cast<int>(col));
}

bool TopGrid::Add(double x, double y, double z, uint16_t point_source_id) {
  const std::optional<size_t> cell = CellOf(x, y);
  if (!cell) return false;
  AddToCell(*cell, z, point_source_id);
  return true;
}

void TopGrid::AddToCell(size_t i, double z, uint16_t point_source_id) {
  if (count[i] < std::numeric_limits<uint32_t>::max()) ++count[i];
  const float zf = static_cast<float>(z);
  if (std::isnan(top_z[i]) || zf > top_z[i]) {
    top_z[i] = zf;
    source_id[i] = point_source_id;
  }
}

TopGridFiller::TopGridFiller(TopGrid* grid, size_t bands)
    : grid_(grid),
      bands_(std::clamp<size_t>(bands, 1, std::max<size_t>(1, static_cast<size_t>(grid->height)))),
      band_of_row_(static_cast<size_t>(std::max(0, grid->height))) {
  const size_t rows = band_of_row_.size();
  for (size_t b = 0; b < bands_; ++b) {
    for (size_t row = rows * b / bands_; row < rows * (b + 1) / bands_; ++row) {
      band_of_row_[row] = static_cast<uint32_t>(b);
    }
  }
}

void TopGridFiller::Add(const std::vector<LasPoint>& points) {
  constexpr size_t kBlock = 4096;
  const TopGrid& grid = *grid_;
  cells_.resize(points.size());
  const size_t blocks = (points.size() + kBlock - 1) / kBlock;
  if (in_band_.size() < blocks * bands_) in_band_.resize(blocks * bands_);
  tbb::parallel_for(size_t{0}, blocks, [&](size_t k) {
    std::vector<uint32_t>* lists = in_band_.data() + k * bands_;
    for (size_t b = 0; b < bands_; ++b) lists[b].clear();
    for (size_t i = k * kBlock; i < std::min(points.size(), (k + 1) * kBlock); ++i) {
      const std::optional<size_t> cell = grid.CellOf(points[i].xyz.x(), points[i].xyz.y());
      if (!cell) continue;
      cells_[i] = *cell;
      lists[band_of_row_[*cell / static_cast<size_t>(grid.width)]].push_back(static_cast<uint32_t>(i));
    }
  });
  tbb::parallel_for(size_t{0}, bands_, [&](size_t b) {
    for (size_t k = 0; k < blocks; ++k) {
      for (const uint32_t i : in_band_[k * bands_ + b]) {
        grid_->AddToCell(cells_[i], points[i].xyz.z(), points[i].point_source_id);
      }
    }
  });
}

double TopGridCellSize(double extent_x_m, double extent_y_m, uint64_t points, int max_cells, double min_cell_m) {
  const double ex = std::max(extent_x_m, 1e-6), ey = std::max(extent_y_m, 1e-6);
  const double spacing = points > 0 ? std::sqrt(ex * ey / static_cast<double>(points)) : 0.0;
  const double by_cap = std::max(ex, ey) / std::max(1, max_cells - 1);
  return std::max({2.5 * spacing, min_cell_m, by_cap});
}

TopGrid MakeTopGrid(double min_x, double min_y, double max_x, double max_y, uint64_t points, int max_cells,
                    double min_cell_m) {
  const double cell = TopGridCellSize(max_x - min_x, max_y - min_y, points, max_cells, min_cell_m);
  // One cell more than the extent needs, the slack split evenly on both sides, so both (inclusive) edges of the
  // box fall strictly inside.
  const int w = std::max(1, static_cast<int>(std::floor((max_x - min_x) / cell)) + 1);
  const int h = std::max(1, static_cast<int>(std::floor((max_y - min_y) / cell)) + 1);
  const double pad_x = 0.5 * (w * cell - (max_x - min_x)), pad_y = 0.5 * (h * cell - (max_y - min_y));
  return TopGrid(min_x - pad_x, max_y + pad_y, cell, w, h);
}

}  // namespace sacfuse
