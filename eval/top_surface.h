#pragma once
// The reference top-surface model: an XY grid holding, per cell, the highest and lowest reference z. Airborne
// LiDAR cannot observe space below the top surface (under roofs, beside walls below the eaves, under canopy),
// and cameras cannot see reference returns from there either. All coordinates are in the local frame of the
// evaluation (float offsets from a double origin).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

class TopSurface {
 public:
  // Throws sacfuse::Error when the grid would need more than max_cells cells (tile the evaluation instead).
  TopSurface(const std::vector<Eigen::Vector3f>& reference, double cell_m, size_t max_cells = 400'000'000);

  // What the reference says about the column at (x, y) and its 8 neighbour cells.
  struct Column {
    bool observed = false;  // at least one reference point in the cell or its 8 neighbours
    float top = 0;          // max reference z over the 3 x 3 cells (roof height next to walls)
    float bottom = 0;       // min reference z over the 3 x 3 cells
    // Height of what hides this column from a camera: max of the own cell's top and, for each of the four
    // opposite neighbour pairs (W-E, S-N, SW-NE, NW-SE), the lower of the pair's tops. A wall on one side does
    // not hide the street beside it; canopy or roofs all around (or on both sides of a narrow slot) do.
    float occluder = 0;
  };
  Column Query(float x, float y) const;

  double cell_m() const { return cell_; }
  // Area of the cells holding at least one reference point, m^2.
  double OccupiedArea() const { return static_cast<double>(occupied_) * cell_ * cell_; }

 private:
  float TopAt(int64_t cx, int64_t cy) const;

  double cell_;
  float x0_ = 0, y0_ = 0;
  int64_t nx_ = 0, ny_ = 0;
  std::vector<float> top_;     // -inf for empty cells
  std::vector<float> bottom_;  // +inf for empty cells
  size_t occupied_ = 0;
};

}  // namespace sacfuse
