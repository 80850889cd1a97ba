#pragma once
// Density normalisation (ETH3D): points grouped by 3D voxel cell, so that a score can be averaged over cells
// instead of points and dense or duplicated regions weigh no more than sparse ones.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

class VoxelGroups {
 public:
  // Groups the points whose `use` flag is non-zero (all when use is null) by cubic voxel of edge voxel_m
  // (grid anchored at the local origin). Cell indices are clamped to +-2^20 per axis, i.e. +-105 km at 0.1 m.
  VoxelGroups(const std::vector<Eigen::Vector3f>& points, double voxel_m, const std::vector<uint8_t>* use = nullptr);

  // Per-point outcome: 0 = not counted, 1 = counted miss, 2 = counted hit. Returns the mean over cells with at
  // least one counted point of (hits / counted) in that cell, and the number of such cells; 0 when none.
  double CellMean(const std::vector<uint8_t>& outcome, uint64_t* cells_counted = nullptr) const;

  size_t num_cells() const { return starts_.empty() ? 0 : starts_.size() - 1; }

 private:
  std::vector<uint32_t> order_;   // point indices sorted by cell
  std::vector<uint32_t> starts_;  // order_[starts_[c] .. starts_[c+1]) is cell c
};

}  // namespace sacfuse
