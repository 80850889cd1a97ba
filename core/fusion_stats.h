#pragma once
// What every fusion method reports (core/fusion_method.h): pixels in and points out per view, the method's named
// counters, histograms and per-view values, and stage times. One type for every method, whole block or tile, so
// tiles add up with one rule (Add) and the run report writes one section.
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sacfuse {

struct FusionStats {
  uint64_t input_pixels = 0;               // valid depth pixels of the views given (that the run owns)
  uint64_t emitted = 0;                    // points written to the sink (tiles: including their halo's)
  std::vector<uint64_t> input_per_view;    // valid depth pixels, indexed like the input views
  std::vector<uint64_t> emitted_per_view;  // indexed like the input views (the point's source view)
  // Named counters of the method (e.g. "removed_redundant"), in a fixed order per method; summed over tiles.
  std::vector<std::pair<std::string, uint64_t>> counters;
  // Named histograms (e.g. SAC's "netlet_size": [members] -> Netlets); summed bin by bin over tiles.
  std::vector<std::pair<std::string, std::vector<uint64_t>>> histograms;
  // Named per-view values (e.g. SAC's estimated "noise_factor"), indexed like the input views; tiles keep the
  // first value a view gets.
  std::vector<std::pair<std::string, std::vector<double>>> view_values;
  std::vector<std::pair<std::string, double>> stage_seconds;  // summed over tiles

  void Count(const std::string& name, uint64_t n) { Accumulate(counters, name, n); }
  uint64_t counter(const std::string& name) const {
    for (const auto& c : counters) {
      if (c.first == name) return c.second;
    }
    return 0;
  }
  void AddStageSeconds(const std::string& stage, double seconds) { Accumulate(stage_seconds, stage, seconds); }
  void AddHistogram(const std::string& name, const std::vector<uint64_t>& bins) {
    auto it = Find(histograms, name);
    if (it == histograms.end()) {
      histograms.emplace_back(name, bins);
      return;
    }
    if (it->second.size() < bins.size()) it->second.resize(bins.size(), 0);
    for (size_t i = 0; i < bins.size(); ++i) it->second[i] += bins[i];
  }
  const std::vector<uint64_t>* histogram(const std::string& name) const {
    for (const auto& h : histograms) {
      if (h.first == name) return &h.second;
    }
    return nullptr;
  }
  const std::vector<double>* view_value(const std::string& name) const {
    for (const auto& v : view_values) {
      if (v.first == name) return &v.second;
    }
    return nullptr;
  }

  // Adds another run's (a tile's) stats. Its per-view vectors are indexed like its own views, which are the
  // views `view_ids[i]` of this one (the block's indices); this one's per-view vectors grow to `num_views`.
  void Add(const FusionStats& o, const std::vector<uint32_t>& view_ids, size_t num_views) {
    input_pixels += o.input_pixels;
    emitted += o.emitted;
    for (const auto& [name, n] : o.counters) Count(name, n);
    for (const auto& [name, bins] : o.histograms) AddHistogram(name, bins);
    for (const auto& [stage, secs] : o.stage_seconds) AddStageSeconds(stage, secs);
    input_per_view.resize(num_views, 0);
    emitted_per_view.resize(num_views, 0);
    for (size_t i = 0; i < view_ids.size(); ++i) {
      if (i < o.input_per_view.size()) input_per_view[view_ids[i]] += o.input_per_view[i];
      if (i < o.emitted_per_view.size()) emitted_per_view[view_ids[i]] += o.emitted_per_view[i];
    }
    for (const auto& [name, values] : o.view_values) {
      auto it = Find(view_values, name);
      if (it == view_values.end()) {
        view_values.emplace_back(name, std::vector<double>(num_views, 0.0));
        it = view_values.end() - 1;
      }
      for (size_t i = 0; i < view_ids.size() && i < values.size(); ++i) {
        if (it->second[view_ids[i]] == 0.0) it->second[view_ids[i]] = values[i];
      }
    }
  }

 private:
  template <typename T>
  static typename std::vector<std::pair<std::string, T>>::iterator Find(std::vector<std::pair<std::string, T>>& entries,
                                                                         const std::string& name) {
    return std::find_if(entries.begin(), entries.end(), [&](const auto& e) { return e.first == name; });
  }
  template <typename T>
  static void Accumulate(std::vector<std::pair<std::string, T>>& entries, const std::string& name, T value) {
    auto it = Find(entries, name);
    if (it == entries.end()) {
      entries.emplace_back(name, value);
    } else {
      it->second += value;
    }
  }
};

}  // namespace sacfuse
