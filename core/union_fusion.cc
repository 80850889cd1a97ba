#include "core/union_fusion.h"

#include "core/method_views.h"

namespace sacfuse {

FusionStats RunUnionFusion(const std::vector<SacView>& views, PointSink& sink) {
  constexpr size_t kChunk = 4096;
  FusionStats stats;
  stats.emitted_per_view.assign(views.size(), 0);
  stats.input_per_view.assign(views.size(), 0);
  std::vector<FusedPoint> chunk;
  chunk.reserve(kChunk);
  for (size_t v = 0; v < views.size(); ++v) {
    const SacView& view = views[v];
    const DepthMap& depth = *view.depth;
    for (int row = 0; row < depth.height; ++row) {
      for (int col = 0; col < depth.width; ++col) {
        const float d = depth.at(row, col);
        if (!IsValidDepth(d)) continue;
        ++stats.emitted_per_view[v];
        FusedPoint p;
        p.point_in_world = PixelPoint(view, row, col, d);
        p.rgb = PixelColour(view, row, col);
        p.view_index = view.view.index;
        chunk.push_back(p);
        if (chunk.size() == kChunk) {
          sink.Write(chunk.data(), chunk.size());
          chunk.clear();
        }
      }
    }
    if (!chunk.empty()) sink.Write(chunk.data(), chunk.size());
    chunk.clear();
    stats.input_pixels += stats.emitted_per_view[v];
    stats.input_per_view[v] = stats.emitted_per_view[v];
  }
  stats.emitted = stats.input_pixels;
  return stats;
}

}  // namespace sacfuse
