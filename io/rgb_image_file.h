#pragma once
// Image files as RGB rasters through OpenCV: any format OpenCV decodes on read (EXIF orientation ignored, as
// COLMAP does, so the raster matches its camera), lossless PNG on write.
#include <string>

#include "core/raster.h"

namespace sacfuse {

// Decodes `path` as 8-bit RGB. Throws InputError naming the file and `who` (e.g. "image \"a.jpg\"") when it is
// missing or undecodable, or (expected_width > 0) when its size is not expected_width x expected_height.
RgbImage ReadRgbImageFile(const std::string& path, const std::string& who, int expected_width = 0,
                          int expected_height = 0);

// Writes an RGB raster as PNG atomically (temporary name, fsync, rename); creates parent folders. Throws Error.
void WriteRgbImagePng(const std::string& path, const RgbImage& image);

}  // namespace sacfuse
