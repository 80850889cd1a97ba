#pragma once
// Colours of a view on its depth raster's grid (depth maps are often at a fraction of the image size).
#include "core/raster.h"

namespace sacfuse {

// `image` (any size with the depth raster's aspect) sampled to depth_width x depth_height exactly as core's
// colour lookup (collapse.cc) samples it: nearest pixel, image row = floor((r + 0.5) * image_height /
// depth_height), clamped; likewise columns. An empty image gives an empty result.
RgbImage ResampleColourToDepthGrid(const RgbImage& image, int depth_width, int depth_height);
// The same for an image the caller gives up: returned as it is when it is depth_width x depth_height already (no
// copy of 3 bytes per pixel of a 50 Mpx view, issue 13), else resampled.
RgbImage ColoursOnDepthGrid(RgbImage image, int depth_width, int depth_height);

}  // namespace sacfuse
