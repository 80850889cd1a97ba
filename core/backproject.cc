#include "core/backproject.h"

#include <algorithm>
#include <vector>

namespace sacfuse {

size_t BackprojectDepthMap(const View& view, const DepthMap& depth, const RgbImage* image, PointSink& sink) {
  const PinholeCamera depth_camera = view.camera.Scaled(depth.width, depth.height);
  const Rigid3d world_from_cam = view.cam_from_world.Inverse();
  const double image_sx = image != nullptr ? static_cast<double>(image->width) / depth.width : 0.0;
  const double image_sy = image != nullptr ? static_cast<double>(image->height) / depth.height : 0.0;
  constexpr size_t kChunk = 4096;
  std::vector<FusedPoint> chunk;
  chunk.reserve(kChunk);
  size_t total = 0;
  for (int row = 0; row < depth.height; ++row) {
    for (int col = 0; col < depth.width; ++col) {
      const float d = depth.at(row, col);
      if (!IsValidDepth(d)) continue;
      FusedPoint p;
      p.point_in_world = DepthPixelToWorld(depth_camera, world_from_cam, col, row, d);
      p.view_index = view.index;
      if (image != nullptr) {
        const int ic = std::min(image->width - 1, static_cast<int>((col + 0.5) * image_sx));
        const int ir = std::min(image->height - 1, static_cast<int>((row + 0.5) * image_sy));
        for (int c = 0; c < 3; ++c) p.rgb[c] = image->at(ir, ic, std::min(c, image->channels - 1));
      }
      chunk.push_back(p);
      if (chunk.size() == kChunk) {
        sink.Write(chunk.data(), chunk.size());
        total += chunk.size();
        chunk.clear();
      }
    }
  }
  if (!chunk.empty()) sink.Write(chunk.data(), chunk.size());
  return total + chunk.size();
}

}  // namespace sacfuse
