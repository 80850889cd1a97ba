#include "eval/voxel_groups.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

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
  // Keys of the used points, in point order: each block of points writes after the used points of the blocks
  // before it (counted first), so the list is the same for any thread count. Every step runs in parallel: a serial
  // step over millions of points (or a serial zero-fill of their buffers) was most of the scoring's serial share.
  constexpr size_t kBlock = 1 << 16;
  const size_t blocks = (points.size() + kBlock - 1) / kBlock;
  std::vector<size_t> first(blocks + 1, 0);
  const auto block_end = [&](size_t b) { return std::min(points.size(), (b + 1) * kBlock); };
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    size_t n = 0;
    for (size_t i = b * kBlock; i < block_end(b); ++i) n += use == nullptr || (*use)[i] != 0;
    first[b + 1] = n;
  });
  for (size_t b = 0; b < blocks; ++b) first[b + 1] += first[b];
  struct Keyed {  // no initialisers: the array is filled in parallel, not zeroed first
    uint64_t key;
    uint32_t index;
    bool operator<(const Keyed& o) const { return key < o.key || (key == o.key && index < o.index); }
  };
  const size_t n = first[blocks];
  const std::unique_ptr<Keyed[]> keyed(new Keyed[n]);
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    size_t k = first[b];
    for (size_t i = b * kBlock; i < block_end(b); ++i) {
      if (use != nullptr && (*use)[i] == 0) continue;
      const auto& p = points[i];
      const uint64_t key = (AxisKey(p.x(), inv) << 42) | (AxisKey(p.y(), inv) << 21) | AxisKey(p.z(), inv);
      keyed[k++] = {key, static_cast<uint32_t>(i)};
    }
  });
  // Entries are distinct (one per point), so the sorted order is unique whichever sort makes it.
  tbb::parallel_sort(keyed.get(), keyed.get() + n);
  // Cell starts: counted per block of the sorted list, then written after the starts of the blocks before it.
  const size_t sorted_blocks = (n + kBlock - 1) / kBlock;
  const auto starts_cell = [&](size_t i) { return i == 0 || keyed[i].key != keyed[i - 1].key; };
  std::vector<size_t> first_start(sorted_blocks + 1, 0);
  tbb::parallel_for(size_t{0}, sorted_blocks, [&](size_t b) {
    size_t cells = 0;
    for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) cells += starts_cell(i);
    first_start[b + 1] = cells;
  });
  for (size_t b = 0; b < sorted_blocks; ++b) first_start[b + 1] += first_start[b];
  order_.resize(n);
  starts_.resize(first_start[sorted_blocks] + 1);
  tbb::parallel_for(size_t{0}, sorted_blocks, [&](size_t b) {
    size_t c = first_start[b];
    for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      order_[i] = keyed[i].index;
      if (starts_cell(i)) starts_[c++] = static_cast<uint32_t>(i);
    }
  });
  starts_.back() = static_cast<uint32_t>(n);
}

double VoxelGroups::CellMean(const std::vector<uint8_t>& outcome, uint64_t* cells_counted) const {
  // Each cell's fraction in parallel (the reads of `outcome` are the cost), then summed in cell order as one loop
  // would: the same double for any thread count.
  const size_t n = num_cells();
  const std::unique_ptr<double[]> fraction(new double[n]);  // every cell written below; -1: no counted point
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c < r.end(); ++c) {
      uint32_t counted = 0, hits = 0;
      for (uint32_t k = starts_[c]; k < starts_[c + 1]; ++k) {
        const uint8_t o = outcome[order_[k]];
        counted += o != 0;
        hits += o == 2;
      }
      fraction[c] = counted > 0 ? static_cast<double>(hits) / counted : -1.0;
    }
  });
  double sum = 0.0;
  uint64_t cells = 0;
  for (size_t c = 0; c < n; ++c) {
    const double f = fraction[c];
    if (f < 0) continue;
    sum += f;
    ++cells;
  }
  if (cells_counted != nullptr) *cells_counted = cells;
  return cells == 0 ? 0.0 : sum / static_cast<double>(cells);
}

}  // namespace sacfuse
