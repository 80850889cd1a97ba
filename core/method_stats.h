#pragma once
// What the comparison fusion methods (consistency, disparity_normal, tsdf, multiray, union) report: pixels in,
// points out per view, method-specific counters and stage times. SAC reports its own SacStats.
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sacfuse {

struct MethodStats {
  uint64_t input_pixels = 0;               // valid depth pixels of the views given
  uint64_t emitted = 0;                    // points written to the sink
  std::vector<uint64_t> input_per_view;    // valid depth pixels, indexed like the input views
  std::vector<uint64_t> emitted_per_view;  // indexed like the input views (the point's source view)
  // Named counters of the method (e.g. "removed_redundant"), in a fixed order per method.
  std::vector<std::pair<std::string, uint64_t>> counters;
  std::vector<std::pair<std::string, double>> stage_seconds;

  void Count(const std::string& name, uint64_t n) {
    auto it = std::find_if(counters.begin(), counters.end(), [&](const auto& c) { return c.first == name; });
    if (it == counters.end()) {
      counters.emplace_back(name, n);
    } else {
      it->second += n;
    }
  }
  uint64_t counter(const std::string& name) const {
    for (const auto& c : counters) {
      if (c.first == name) return c.second;
    }
    return 0;
  }
  // Adds another run's (a tile's) totals; emitted_per_view is not touched (its indices are the other run's).
  void Add(const MethodStats& o) {
    input_pixels += o.input_pixels;
    emitted += o.emitted;
    for (const auto& [name, n] : o.counters) Count(name, n);
    for (const auto& entry : o.stage_seconds) {  // (not a structured binding: clang 14 cannot capture one)
      auto it = std::find_if(stage_seconds.begin(), stage_seconds.end(),
                             [&](const auto& e) { return e.first == entry.first; });
      if (it == stage_seconds.end()) {
        stage_seconds.push_back(entry);
      } else {
        it->second += entry.second;
      }
    }
  }
};

}  // namespace sacfuse
