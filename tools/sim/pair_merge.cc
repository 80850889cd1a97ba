#include "tools/sim/pair_merge.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sacfuse::sim {
namespace {

// Median of values[0..n) (reordered); the mean of the two middle values for an even n.
double MedianOf(double* values, size_t n) {
  std::sort(values, values + n);
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

PairMerge MergePairDepths(const std::vector<DepthMap>& pair_depths, double relative_tolerance, int min_agree) {
  PairMerge merged;
  if (pair_depths.empty()) return merged;
  const int width = pair_depths[0].width, height = pair_depths[0].height;
  for (const DepthMap& d : pair_depths) {
    if (d.width != width || d.height != height || d.channels != 1) {
      throw std::invalid_argument("MergePairDepths: the pair depth maps differ in size");
    }
  }
  merged.depth = DepthMap(width, height, 1, 0.0f);
  merged.agreeing.assign(merged.depth.num_pixels(), 0);
  std::vector<double> valid(pair_depths.size()), agreeing(pair_depths.size());
  for (size_t p = 0; p < merged.depth.num_pixels(); ++p) {
    size_t n = 0;
    for (const DepthMap& d : pair_depths) {
      if (IsValidDepth(d.data[p])) valid[n++] = d.data[p];
    }
    if (n == 0) continue;
    const double median = MedianOf(valid.data(), n);
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
      if (std::abs(valid[i] - median) <= relative_tolerance * median) agreeing[k++] = valid[i];
    }
    merged.agreeing[p] = static_cast<uint8_t>(std::min<size_t>(k, 255));
    if (k == 0 || static_cast<int>(k) < min_agree) continue;
    merged.depth.data[p] = static_cast<float>(MedianOf(agreeing.data(), k));
  }
  return merged;
}

}  // namespace sacfuse::sim
