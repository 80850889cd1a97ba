#pragma once
// Colours of a view on its depth raster's grid (depth maps are often at a fraction of the image size).
#include "core/raster.h"

namespace sacfuse {

// `image` (any size with the depth raster's aspect) sampled to depth_width x depth_height exactly as core's
// colour lookup (collapse.cc) samples it: nearest pixel, image row = floor((r + 0.5) * image_height /
// depth_height), clamped; likewise columns. An empty image gives an empty result.
RgbImage ResampleColourToDepthGrid(const RgbImage& image, int depth_width, int depth_height);
// Whether `image` is depth_width x depth_height already: ResampleColourToDepthGrid would return a copy of it.
inline bool IsOnDepthGrid(const RgbImage& image, int depth_width, int depth_height) {
  return !image.empty() && image.width == depth_width && image.height == depth_height;
}

}  // namespace sacfuse
