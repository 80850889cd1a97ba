#pragma once
// Raster product files through GDAL (Debian's libgdal): the per-tile intermediates of a run, Cloud Optimized
// GeoTIFFs, and VRT mosaics, all on the cell lattice of core/cell_window.h (north-up, square cells, origin on a
// multiple of the cell). Every file is written under a temporary name (io/atomic_file.h), fsynced and renamed, so
// a killed process never leaves a complete-looking partial raster. GDAL's block cache is capped
// (kGdalCacheBytes) so writing a block-sized raster does not grow with the machine's RAM.
//
// Layouts (RasterLayout):
//   kIntermediate  GeoTIFF, 256 x 256 internal tiles, DEFLATE with the floating-point predictor for float32
//                  (horizontal for bytes), no overviews: per-tile files a run reads back.
//   kCog           Cloud Optimized GeoTIFF (GDAL's COG driver): 512 x 512 internal tiles, DEFLATE with the
//                  predictor, overviews (RasterFormat::overview_resampling) down to one tile, BigTIFF when
//                  needed; the overviews are built into a temporary GeoTIFF first so the COG driver writes no
//                  side file of its own.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/cell_window.h"

namespace sacfuse {

constexpr int64_t kGdalCacheBytes = int64_t{256} << 20;

enum class RasterSampleType { kFloat32, kByte };
enum class RasterLayout { kIntermediate, kCog };

// What a raster product file holds.
struct RasterFormat {
  int bands = 1;
  RasterSampleType type = RasterSampleType::kFloat32;
  std::optional<double> nodata;    // of every band (NaN allowed for float32)
  std::string crs_wkt;             // "" = no CRS
  std::string overview_resampling = "AVERAGE";  // GDAL resampling of COG overviews
  std::vector<std::string> band_descriptions;   // optional, one per band
  bool rgba = false;  // 4 byte bands read as red, green, blue and alpha (the alpha band masks the others)
};

size_t SampleBytes(RasterSampleType type);

// Writes one raster of `window`: `data` holds bands one after the other, each north-up (CellWindow::Index),
// window.size() samples of the format's type per band. Atomic; throws Error naming the path.
void WriteRasterFile(const std::string& path, const CellWindow& window, const RasterFormat& format,
                     const void* data, RasterLayout layout);

// CogBuilder's temporary GeoTIFF is uncompressed for rasters of at most this many bytes (all bands).
constexpr uint64_t kCogUncompressedBytes = uint64_t{64} << 20;

// Builds one COG of a large extent block by block: blocks go into a temporary tiled GeoTIFF beside `path`
// (uncompressed up to kCogUncompressedBytes, else DEFLATE level 1), Finish() adds the overviews and translates it
// into the COG at `path` (atomically); the temporary file is removed. The COG's bytes do not depend on how the
// temporary file was stored. A builder destroyed before Finish() leaves nothing at `path` and removes its
// temporary files.
class CogBuilder {
 public:
  // `uncompressed_temp_bytes`: the largest raster (all bands) whose temporary GeoTIFF is left uncompressed.
  CogBuilder(const std::string& path, const CellWindow& extent, const RasterFormat& format,
             uint64_t uncompressed_temp_bytes = kCogUncompressedBytes);
  ~CogBuilder();
  CogBuilder(const CogBuilder&) = delete;
  CogBuilder& operator=(const CogBuilder&) = delete;
  // `block` must lie inside the extent; `data` as for WriteRasterFile. Cells never written stay nodata.
  void Write(const CellWindow& block, const void* data);
  void Finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A raster GDAL opens (GeoTIFF, VRT, ...), read on the lattice.
class RasterFile {
 public:
  // Throws InputError naming the file when GDAL cannot open it, it is rotated, its cells are not square, or
  // (lattice = true) its origin is not on a multiple of its cell.
  explicit RasterFile(const std::string& path, bool lattice = true);
  ~RasterFile();
  RasterFile(RasterFile&&) noexcept;
  RasterFile& operator=(RasterFile&&) noexcept;

  const std::string& path() const;
  // Its cells; for a file off the lattice (lattice = false) col0/row0 are those of the lattice cell holding its
  // north-west cell's centre.
  const CellWindow& window() const;
  int bands() const;
  std::optional<double> nodata(int band = 1) const;
  std::string crs_wkt() const;
  // The cells of `w` (same cell size) of band `band` (1-based) as float, north-up; cells outside the file and
  // nodata cells are NaN.
  std::vector<float> ReadFloat(const CellWindow& w, int band = 1) const;
  // The whole band resampled to at most max_side x max_side samples (GDAL's overviews when present, averaging),
  // north-up; nodata = NaN. *cols and *rows receive the size read.
  std::vector<float> ReadOverview(int max_side, int* cols, int* rows, int band = 1) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A VRT at `vrt_path` over `sources` (paths relative to the VRT's folder when below it), atomically. Throws Error.
void WriteVrt(const std::string& vrt_path, const std::vector<std::string>& sources);

}  // namespace sacfuse
