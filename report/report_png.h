#pragma once
// PNG files of the run report's pictures (OpenCV imgcodecs), written atomically.
#include <string>

#include "core/raster.h"

namespace sacfuse {

// PNG bytes of an RGB image (3 channels). Throws Error when encoding fails.
std::string EncodePng(const RgbImage& image);
// Encodes and writes atomically (io/atomic_file.h).
void WritePng(const std::string& path, const RgbImage& image);

}  // namespace sacfuse
