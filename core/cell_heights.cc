#include "core/cell_heights.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "core/error.h"

namespace sacfuse {
namespace {

// Bits of a float whose unsigned order is the float order (negative values reversed below the positive ones).
uint32_t OrderedBits(float v) {
  uint32_t b = 0;
  std::memcpy(&b, &v, sizeof(b));
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}

float FromOrderedBits(uint32_t b) {
  b = (b & 0x80000000u) ? (b & 0x7fffffffu) : ~b;
  float v = 0;
  std::memcpy(&v, &b, sizeof(v));
  return v;
}

// No key: a raster index of 2^32 - 1 is never a cell's (windows have fewer than 2^32 cells).
constexpr uint64_t kNoKey = ~uint64_t{0};

// The position of the q-quantile among `count` sorted values (count > 0).
size_t QuantilePosition(size_t count, double quantile) {
  return std::min(count - 1, static_cast<size_t>(std::floor(quantile * (count - 1) + 0.5)));
}

}  // namespace

float CellValueOf(std::vector<float>* z, double quantile, int min_points) {
  if (z->empty() || static_cast<int64_t>(z->size()) < min_points) return kNoCellValue;
  std::vector<uint32_t> bits(z->size());
  for (size_t i = 0; i < z->size(); ++i) bits[i] = OrderedBits((*z)[i]);
  std::sort(bits.begin(), bits.end());  // the order Reduce sorts in (-0 below +0)
  for (size_t i = 0; i < z->size(); ++i) (*z)[i] = FromOrderedBits(bits[i]);
  return (*z)[QuantilePosition(z->size(), quantile)];
}

CellHeights::CellHeights(const CellWindow& window) : window_(window) {
  if (window.size() >= (uint64_t{1} << 32)) {
    throw Error("cell window of " + std::to_string(window.cols) + " x " + std::to_string(window.rows) +
                " cells is too large to grid at once (at most 2^32 cells)");
  }
}

bool CellHeights::CellOf(double x, double y, int64_t* col, int64_t* row) const {
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  *col = CellIndexOf(x, window_.cell_m);
  *row = CellIndexOf(y, window_.cell_m);
  return window_.Contains(*col, *row);
}

void CellHeights::Add(double x, double y, double z) {
  int64_t col = 0, row = 0;
  if (!std::isfinite(z) || !CellOf(x, y, &col, &row)) {
    ++ignored_;
    return;
  }
  AddToCell(col, row, z);
}

void CellHeights::AddToCell(int64_t col, int64_t row, double z) {
  if (!std::isfinite(z)) {
    ++ignored_;
    return;
  }
  keys_.push_back((static_cast<uint64_t>(window_.Index(col, row)) << 32) | OrderedBits(static_cast<float>(z)));
}

void CellHeights::AddInParallel(size_t count, const PointCell& point_cell) {
  const size_t first = keys_.size();
  keys_.resize(first + count);
  std::atomic<uint64_t> ignored{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& range) {
    uint64_t range_ignored = 0;
    for (size_t i = range.begin(); i < range.end(); ++i) {
      int64_t col = 0, row = 0;
      double z = 0;
      uint64_t& key = keys_[first + i];
      key = kNoKey;
      if (!point_cell(i, &col, &row, &z)) continue;
      if (!std::isfinite(z)) {
        ++range_ignored;
        continue;
      }
      key = (static_cast<uint64_t>(window_.Index(col, row)) << 32) | OrderedBits(static_cast<float>(z));
    }
    ignored += range_ignored;
  });
  keys_.erase(std::remove(keys_.begin() + static_cast<std::ptrdiff_t>(first), keys_.end(), kNoKey), keys_.end());
  ignored_ += ignored.load();
}

std::vector<float> CellHeights::Reduce(double quantile, int min_points) {
  std::vector<float> values(window_.size(), kNoCellValue);
  tbb::parallel_sort(keys_.begin(), keys_.end());  // equal keys are equal values: the order is the serial sort's
  // The sorted keys in ranges on the job's threads, each range's cells those whose first key lies in it (a cell's
  // keys are contiguous, so every cell is reduced once, by one range).
  const size_t n = keys_.size();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, size_t{1} << 16), [&](const tbb::blocked_range<size_t>& r) {
    size_t begin = r.begin();
    while (begin > 0 && begin < n && (keys_[begin - 1] >> 32) == (keys_[begin] >> 32)) ++begin;  // the cell's start
    while (begin < r.end()) {
      const uint64_t cell = keys_[begin] >> 32;
      size_t end = begin + 1;
      while (end < n && (keys_[end] >> 32) == cell) ++end;
      const size_t count = end - begin;
      if (static_cast<int64_t>(count) >= min_points) {
        const size_t k = QuantilePosition(count, quantile);
        values[cell] = FromOrderedBits(static_cast<uint32_t>(keys_[begin + k] & 0xffffffffu));
      }
      begin = end;
    }
  });
  keys_.clear();
  keys_.shrink_to_fit();
  return values;
}

}  // namespace sacfuse
