#include "core/cluster_adjacency.h"

#include <algorithm>
#include <string>

#include <tbb/parallel_for.h>

#include "core/error.h"

namespace sacfuse {

std::vector<std::vector<uint32_t>> ClusterAdjacency(const SuperpixelMap& map) {
  const size_t n = map.clusters.size();
  if (map.width < 0 || map.height < 0 ||
      map.labels.width() != map.width || map.labels.height() != map.height) {
    throw Error("ClusterAdjacency: labels do not match width x height");
  }
  constexpr int kBandRows = 64;
  const int bands = (map.height + kBandRows - 1) / kBandRows;
  std::vector<std::vector<uint64_t>> band_pairs(static_cast<size_t>(bands));
  const auto key = [](uint32_t a, uint32_t b) {
    return a < b ? (static_cast<uint64_t>(a) << 32) | b : (static_cast<uint64_t>(b) << 32) | a;
  };
  tbb::parallel_for(0, bands, [&](int band) {
    std::vector<uint64_t>& pairs = band_pairs[static_cast<size_t>(band)];
    const int row_end = std::min(map.height, (band + 1) * kBandRows);
    uint64_t last = ~0ull;
    const auto add = [&](int32_t a, int32_t b) {
      if (a == b) return;
      const uint64_t k = key(static_cast<uint32_t>(a), static_cast<uint32_t>(b));
      if (k != last) pairs.push_back(k);
      last = k;
    };
    std::vector<int32_t> rows(2 * static_cast<size_t>(map.width));
    int32_t* here = rows.data();
    int32_t* below = here + map.width;
    if (band * kBandRows < row_end) map.labels.CopyRow(band * kBandRows, below);
    for (int row = band * kBandRows; row < row_end; ++row) {
      std::swap(here, below);
      const bool has_below = row + 1 < map.height;
      if (has_below) map.labels.CopyRow(row + 1, below);
      for (int col = 0; col < map.width; ++col) {
        if (here[col] < 0 || static_cast<size_t>(here[col]) >= n) {
          throw Error("ClusterAdjacency: label " + std::to_string(here[col]) + " out of range at row " +
                      std::to_string(row) + ", col " + std::to_string(col));
        }
        if (col + 1 < map.width) add(here[col], here[col + 1]);
        if (has_below) add(here[col], below[col]);
      }
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  });
  std::vector<uint64_t> all;
  for (auto& pairs : band_pairs) {
    all.insert(all.end(), pairs.begin(), pairs.end());
    std::vector<uint64_t>().swap(pairs);
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());

  std::vector<std::vector<uint32_t>> adjacency(n);
  for (uint64_t k : all) {
    const auto a = static_cast<uint32_t>(k >> 32);
    const auto b = static_cast<uint32_t>(k & 0xffffffffu);
    adjacency[a].push_back(b);
    adjacency[b].push_back(a);
  }
  // Pairs are sorted by (a, b): each list received its larger neighbours in order but smaller ones interleaved.
  for (auto& list : adjacency) std::sort(list.begin(), list.end());
  return adjacency;
}

}  // namespace sacfuse
