#pragma once
// Depth rasters as single-band float32 TIFF (striped or tiled, any compression libtiff decodes: none, LZW,
// Deflate, with or without the floating-point predictor; classic TIFF or BigTIFF), as photogrammetry tools and
// GDAL write them. Only the first image of a multi-page file is read.
//
// Values are depths in metres. A pixel is INVALID (returned as 0) when it is NaN or infinite, <= 0, or equal to
// the GDAL_NODATA tag (TIFF tag 42113, ASCII, e.g. "-9999" or "nan") when the file has one. Row 0 is the top row
// (the Orientation tag, when present, must be 1 = top-left).
//
// Every error is an InputError naming the file: not a TIFF, truncated, not float32 (e.g. 16-bit integer or
// float64), several bands, a bad GDAL_NODATA text, a strip or tile that fails to decode. libtiff's own error and
// warning messages never reach stderr: they are collected per file and appended to the exception's message; the
// warnings about a file that is read successfully are logged as a warning naming it (io/input_warnings.h).
#include <memory>
#include <optional>
#include <string>

#include "core/pixel_window.h"
#include "core/raster.h"

namespace sacfuse {

struct TiffDepthInfo {
  int width = 0, height = 0;  // pixels
  bool tiled = false;
  int block_width = 0;           // tile width, or the image width for strips
  int block_height = 0;          // tile height, or rows per strip
  int compression = 1;           // TIFF Compression tag (1 none, 5 LZW, 8 Deflate, ...)
  std::optional<double> nodata;  // from GDAL_NODATA (may be NaN)
};

// An open depth raster for several window reads (one header parse). Not thread-safe; open one per thread.
class TiffDepthReader {
 public:
  explicit TiffDepthReader(const std::string& path);  // reads the header; throws InputError naming the file
  ~TiffDepthReader();
  TiffDepthReader(const TiffDepthReader&) = delete;
  TiffDepthReader& operator=(const TiffDepthReader&) = delete;

  const TiffDepthInfo& info() const { return info_; }
  // See ReadTiffDepthWindow.
  DepthMap ReadWindow(const PixelWindow& window);

 private:
  struct Impl;
  std::string path_;
  TiffDepthInfo info_;
  std::unique_ptr<Impl> impl_;
};

// Header only. Throws InputError naming the file.
TiffDepthInfo ReadTiffDepthInfo(const std::string& path);
// The whole raster (invalid pixels 0).
DepthMap ReadTiffDepth(const std::string& path);
// The pixels of `window` only: decodes just the strips (rows) or tiles that intersect it. Throws InputError for
// a bad file, Error for a window outside the raster.
DepthMap ReadTiffDepthWindow(const std::string& path, const PixelWindow& window);

struct TiffDepthWriteOptions {
  bool tiled = true;        // tiles (true) or strips (false)
  int tile_size_px = 256;   // tile edge, pixels; a multiple of 16 (TIFF rule)
  int rows_per_strip = 16;  // strips: rows per strip, >= 1
  enum class Compression { kNone, kLzw, kDeflate };
  Compression compression = Compression::kDeflate;  // LZW/Deflate use the floating-point predictor (3)
  // When set, invalid pixels (IsValidDepth false) are written as this value and GDAL_NODATA records it (NaN is
  // written as "nan"); when unset, values are written exactly as given and no GDAL_NODATA tag is written.
  std::optional<float> nodata = std::nullopt;
};

// Writes a single-band float32 TIFF atomically (temporary name, fsync, rename); creates parent folders. BigTIFF
// when the uncompressed data exceed 2 GiB. Throws Error naming the file.
void WriteTiffDepth(const std::string& path, const DepthMap& depth, const TiffDepthWriteOptions& options = {});

}  // namespace sacfuse
