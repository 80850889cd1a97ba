#include "core/sac_view.h"

#include <algorithm>

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
