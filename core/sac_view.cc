#include "core/sac_view.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {

SacView MakeSacView(const View& view, const DepthMap* depth, const SuperpixelMap* superpixels, const RgbImage* image,
                    const ConsistencyGraph* consistency) {
  SacView v;
  v.view = view;
  v.depth = depth;
  v.superpixels = superpixels;
  v.image = image;
  v.consistency = consistency;
  v.depth_camera = view.camera.Scaled(depth->width, depth->height);
  v.world_from_cam = view.cam_from_world.Inverse();
  v.cam_from_world_rotation = view.cam_from_world.rotation.toRotationMatrix();
  v.cam_from_world_translation = view.cam_from_world.translation;
  return v;
}

DepthLookup LookupDepth(const SacView& view, const Eigen::Vector3d& point_in_world) {
  return LookupDepthInCamera(view, view.PointInCamera(point_in_world));
}

DepthLookup ProjectIntoDepth(const SacView& view, const Eigen::Vector3d& point_in_camera) {
  DepthLookup out;
  if (point_in_camera.z() <= 0) return out;
  const Eigen::Vector2d uv = view.depth_camera.Project(point_in_camera);
  if (!(uv.x() >= 0 && uv.y() >= 0 && uv.x() < view.depth->width && uv.y() < view.depth->height)) return out;
  out.inside = true;
  out.col = static_cast<int>(uv.x());
  out.row = static_cast<int>(uv.y());
  out.z_m = point_in_camera.z();
  return out;
}

DepthLookup LookupDepthInCamera(const SacView& view, const Eigen::Vector3d& point_in_camera) {
  DepthLookup out = ProjectIntoDepth(view, point_in_camera);
  if (out.inside) out.stored_depth_m = view.depth->at(out.row, out.col);
  return out;
}

void PrefetchDepthAround(const SacView& view, const ViewPoint& at) {
  if (!at.in_front) return;
  // Pixel centres at +0.5: the sample's top-left pixel, clamped so that its 2 x 2 block lies inside.
  const double x = at.uv.x() - 0.5, y = at.uv.y() - 0.5;
  const DepthMap& depth = *view.depth;
  if (!(x >= -1.0 && y >= -1.0 && x < depth.width && y < depth.height)) return;
  const int col = std::clamp(static_cast<int>(std::floor(x)), 0, depth.width - 1);
  const int row = std::clamp(static_cast<int>(std::floor(y)), 0, std::max(0, depth.height - 2));
  PrefetchDepthPixel(view, row, col);
  if (row + 1 < depth.height) PrefetchDepthPixel(view, row + 1, col);
}

std::array<uint8_t, 3> PixelColour(const SacView& view, int row, int col) {
  if (view.image == nullptr || view.image->empty()) return {128, 128, 128};
  return PixelColour(view.image, *view.depth, row, col);
}

std::array<uint8_t, 3> PixelColour(const RgbImage* image, const DepthMap& depth, int row, int col) {
  if (image == nullptr || image->empty()) return {128, 128, 128};
  const RgbImage& img = *image;
  const int ic = std::min(img.width - 1, static_cast<int>((col + 0.5) * img.width / depth.width));
  const int ir = std::min(img.height - 1, static_cast<int>((row + 0.5) * img.height / depth.height));
  std::array<uint8_t, 3> rgb;
  for (int c = 0; c < 3; ++c) rgb[c] = img.at(ir, ic, std::min(c, img.channels - 1));
  return rgb;
}

}  // namespace sacfuse
