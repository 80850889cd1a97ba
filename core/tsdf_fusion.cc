#include "core/tsdf_fusion.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/option_check.h"
#include "core/tsdf_volume.h"

namespace sacfuse {

void ValidateTsdfOptions(const TsdfOptions& o) {
  OptionChecker c;
  c.Greater("TsdfOptions.voxel_size_gsd", o.voxel_size_gsd, 0.0);
  c.Require(o.truncation_gsd > o.voxel_size_gsd, "TsdfOptions.truncation_gsd",
            OptionChecker::ToString(o.truncation_gsd),
            "must be > voxel_size_gsd (" + OptionChecker::ToString(o.voxel_size_gsd) + ")");
  c.AtLeast("TsdfOptions.min_weight", o.min_weight, 1.0);
  c.AtLeast("TsdfOptions.max_memory_gb", o.max_memory_gb, 0.0);
  c.ThrowIfFailed("tsdf options");
}

double MedianGsdFromDepth(const std::vector<SacView>& views) {
  std::vector<double> gsd;
  for (const SacView& view : views) {
    std::vector<float> depths;
    for (int row = 2; row < view.depth->height; row += 4) {
      for (int col = 2; col < view.depth->width; col += 4) {
        const float d = view.depth->at(row, col);
        if (IsValidDepth(d)) depths.push_back(d);
      }
    }
    if (depths.empty()) continue;
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    gsd.push_back(view.GsdAt(depths[depths.size() / 2]));
  }
  if (gsd.empty()) return 0.0;
  std::nth_element(gsd.begin(), gsd.begin() + gsd.size() / 2, gsd.end());
  return gsd[gsd.size() / 2];
}

FusionStats RunTsdfFusion(const std::vector<SacView>& views, const TsdfOptions& options, PointSink& sink,
                          double gsd_m, const Box2d* region_xy) {
  ValidateTsdfOptions(options);
  FusionStats stats;
  stats.emitted_per_view.assign(views.size(), 0);
  stats.input_per_view.assign(views.size(), 0);
  for (size_t v = 0; v < views.size(); ++v) {
    for (const float d : views[v].depth->data) stats.input_per_view[v] += IsValidDepth(d) ? 1 : 0;
    stats.input_pixels += stats.input_per_view[v];
  }
  if (gsd_m <= 0) gsd_m = MedianGsdFromDepth(views);
  if (gsd_m <= 0) return stats;  // no valid depth anywhere
  auto start = std::chrono::steady_clock::now();
  const uint64_t max_bytes = options.max_memory_gb > 0
                                 ? static_cast<uint64_t>(options.max_memory_gb * static_cast<double>(uint64_t{1} << 30))
                                 : UINT64_MAX;
  TsdfVolume volume(options.voxel_size_gsd * gsd_m, options.truncation_gsd * gsd_m, max_bytes);
  if (region_xy != nullptr) volume.RestrictTo(*region_xy);
  for (uint32_t v = 0; v < views.size(); ++v) volume.Integrate(views, v);
  auto now = std::chrono::steady_clock::now();
  stats.stage_seconds.emplace_back("integrate", std::chrono::duration<double>(now - start).count());
  start = now;
  volume.ExtractPoints(views, options.min_weight, sink, &stats);
  stats.stage_seconds.emplace_back(
      "extract", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  stats.Count("voxel_blocks", volume.num_blocks());
  stats.Count("voxels", volume.num_blocks() * static_cast<uint64_t>(kTsdfBlockVoxels));
  return stats;
}

}  // namespace sacfuse
