#pragma once
// COLMAP dense arrays (stereo/depth_maps/*.bin, stereo/normal_maps/*.bin): an ASCII header "W&H&C&" followed
// by W*H*C little-endian float32 values in CHANNEL-PLANAR order (index = c*W*H + row*W + col). In memory we
// use sacfuse::Raster (channel-interleaved); the conversion happens here.
#include <string>

#include "core/pixel_window.h"
#include "core/raster.h"

namespace sacfuse {

struct ColmapArrayShape {
  int width = 0;
  int height = 0;
  int channels = 0;
  size_t data_offset = 0;  // bytes from the file start to the first float
};

// Reads only the header. Throws InputError (file named) for a malformed header or a file whose size does not
// match W*H*C floats.
ColmapArrayShape ReadColmapArrayShape(const std::string& path);
Raster<float> ReadColmapArray(const std::string& path);
// Rows [row_begin, row_end) of every channel; used by tiles that need a window.
Raster<float> ReadColmapArrayRows(const std::string& path, int row_begin, int row_end);
// The pixels of `window`, every channel (one seek + read per row and channel, so a narrow window of a wide map
// reads only its columns). Throws InputError for a bad file, Error for a window outside the array.
Raster<float> ReadColmapArrayWindow(const std::string& path, const PixelWindow& window);
// The rows `rows` (each in [0, height), any order) at full width, every channel: row i of the result is rows[i]
// of the array. One seek + read per row and channel, so every k-th row reads 1 / k of the file. Throws InputError
// for a bad file, Error for a row outside the array.
Raster<float> ReadColmapArrayRowList(const std::string& path, const std::vector<int>& rows);
// Writes atomically (temporary name, fsync, rename).
void WriteColmapArray(const std::string& path, const Raster<float>& raster);

}  // namespace sacfuse
