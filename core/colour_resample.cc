#include "core/colour_resample.h"

#include <algorithm>
#include <vector>

namespace sacfuse {

RgbImage ResampleColourToDepthGrid(const RgbImage& image, int depth_width, int depth_height) {
  if (image.empty() || depth_width <= 0 || depth_height <= 0) return RgbImage();
  RgbImage out(depth_width, depth_height, image.channels);
  std::vector<int> source_col(static_cast<size_t>(depth_width));
  for (int c = 0; c < depth_width; ++c) {
    source_col[c] = std::min(image.width - 1, static_cast<int>((c + 0.5) * image.width / depth_width));
  }
  for (int r = 0; r < depth_height; ++r) {
    const int ir = std::min(image.height - 1, static_cast<int>((r + 0.5) * image.height / depth_height));
    for (int c = 0; c < depth_width; ++c) {
      for (int ch = 0; ch < image.channels; ++ch) out.at(r, c, ch) = image.at(ir, source_col[c], ch);
    }
  }
  return out;
}

RgbImage ColoursOnDepthGrid(RgbImage image, int depth_width, int depth_height) {
  if (!image.empty() && image.width == depth_width && image.height == depth_height) return image;
  return ResampleColourToDepthGrid(image, depth_width, depth_height);
}

}  // namespace sacfuse
