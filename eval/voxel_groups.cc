#include "eval/voxel_groups.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sacfuse {
namespace {

uint64_t AxisKey(float v, double inv_voxel) {
  constexpr double kHalf = 1 << 20;
  const double c = std::floor(static_cast<double>(v) * inv_voxel);
  const double clamped = std::clamp(c, -kHalf, kHalf - 1.0);  // also maps NaN-free huge values to the border
  return static_cast<uint64_t>(clamped + kHalf);             // 21 bits
}

}  // namespace

VoxelGroups::VoxelGroups(const std::vector<Eigen::Vector3f>& points, double voxel_m,
                         const std::vector<uint8_t>* use) {
  const double inv = 1.0 / voxel_m;
  std::vector<std::pair<uint64_t, uint32_t>> keyed;
  keyed.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (use != nullptr && (*use)[i] == 0) continue;
    const auto& p = points[i];
    const uint64_t key = (AxisKey(p.x(), inv) << 42) | (AxisKey(p.y(), inv) << 21) | AxisKey(p.z(), inv);
    keyed.emplace_back(key, static_cast<uint32_t>(i));
  }
  std::sort(keyed.begin(), keyed.end());
  order_.resize(keyed.size());
  for (size_t i = 0; i < keyed.size(); ++i) {
    order_[i] = keyed[i].second;
    if (i == 0 || keyed[i].first != keyed[i - 1].first) starts_.push_back(static_cast<uint32_t>(i));
  }
  starts_.push_back(static_cast<uint32_t>(keyed.size()));
}

double VoxelGroups::CellMean(const std::vector<uint8_t>& outcome, uint64_t* cells_counted) const {
  double sum = 0.0;
  uint64_t cells = 0;
  for (size_t c = 0; c + 1 < starts_.size(); ++c) {
    uint32_t counted = 0, hits = 0;
    for (uint32_t k = starts_[c]; k < starts_[c + 1]; ++k) {
      const uint8_t o = outcome[order_[k]];
      counted += o != 0;
      hits += o == 2;
    }
    if (counted == 0) continue;
    sum += static_cast<double>(hits) / counted;
    ++cells;
  }
  if (cells_counted != nullptr) *cells_counted = cells;
  return cells == 0 ? 0.0 : sum / static_cast<double>(cells);
}

}  // namespace sacfuse
