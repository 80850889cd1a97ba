#pragma once
// A view's colours resampled to its depth raster, stored once (next to its superpixels) so tiles read colour
// windows by row instead of decoding the whole image for every tile.
//
// Binary layout, little-endian: char[8] "SACRGB01", u32 width, u32 height, u32 channels (1 or 3), u32 zero
// (24-byte header), then u8 pixels[height][width][channels] row-major. The file length must match exactly.
#include <string>

#include "core/pixel_window.h"
#include "core/raster.h"

namespace sacfuse {

// Atomic (temp file, fsync, rename); creates missing parent folders. Throws Error for an empty raster or a
// write failure.
void WriteColourRaster(const std::string& path, const RgbImage& image);

struct ColourRasterInfo {
  int width = 0, height = 0, channels = 0;
};
// Header only (also checks the file length). Throws InputError naming the file.
ColourRasterInfo ReadColourRasterInfo(const std::string& path);

// The pixels of `window` (one seek + read per row). Throws InputError for a bad file, Error for a window outside
// the raster.
RgbImage ReadColourRasterWindow(const std::string& path, const PixelWindow& window);

}  // namespace sacfuse
