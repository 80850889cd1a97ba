#pragma once
// Writing a raster product of a whole extent block by block, in bounded memory: each block of kAssemblyBlockCells
// x kAssemblyBlockCells cells (core/cell_window.h CellBlocksOf, aligned on the global lattice) is computed from
// the raw cells of the block plus a halo (`finish`, e.g. the DSM's hole filling,
// core/dsm_rule.h), then written either
//   - into one Cloud Optimized GeoTIFF of the extent (RasterOutput::single_path; io/gdal_raster.h CogBuilder), or
//   - as one COG per block, <blocks_dir>/<bx>_<by>.tif, with a VRT mosaic over them at vrt_path (for extents too
//     large for one file: RasterLayoutFor).
// The result does not depend on how the raw cells were produced (one tile, many tiles, a whole cloud), only on
// their values.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/cell_window.h"
#include "io/gdal_raster.h"

namespace sacfuse {

constexpr int64_t kAssemblyBlockCells = 2048;
// Extents with more cells are written as blocks + VRT by the automatic layout (2^30 cells: 4 GiB of float32,
// e.g. 32768 x 32768 cells, 6.5 km x 6.5 km at 0.2 m).
constexpr uint64_t kSingleFileMaxCells = uint64_t{1} << 30;

struct RasterOutput {
  bool blocks = false;        // false: one COG at single_path; true: block COGs in blocks_dir + VRT at vrt_path
  std::string single_path;
  std::string blocks_dir;
  std::string vrt_path;
};

// "auto" -> blocks when the extent has more than kSingleFileMaxCells cells; "single" | "tiles" as given.
bool RasterLayoutIsBlocks(const std::string& layout, const CellWindow& extent);

// The raw cells of a window (north-up, NaN = none; cells outside the raw data NaN).
using RawCellReader = std::function<std::vector<float>(const CellWindow& window)>;
// The finished cells of `inner` from the raw cells of `outer` (= inner grown by the halo).
using CellFinisher =
    std::function<std::vector<float>(const std::vector<float>& raw, const CellWindow& outer, const CellWindow& inner)>;

struct AssemblyStats {
  uint64_t cells = 0;         // of the extent
  uint64_t cells_with_value = 0;
  size_t blocks = 0;
  std::vector<std::string> files;  // written (the COG, or the VRT and its block files)
};

// The finished cells of one block in the format's layout (bands one after the other, each north-up, the format's
// sample type), adding to *cells_with_value the block's cells that have a value.
using BlockMaker = std::function<std::vector<uint8_t>(const CellWindow& block, uint64_t* cells_with_value)>;

// Writes any product of `extent` block by block (blocks of kAssemblyBlockCells, in CellBlocksOf order) into the
// output's layout. Files of an earlier assembly in `blocks_dir` that this one does not write are removed. Throws
// Error.
AssemblyStats AssembleRasterBlocks(const CellWindow& extent, const BlockMaker& make, const RasterFormat& format,
                                   const RasterOutput& output);

// The single-band float32 products (format.bands must be 1): each block finished from its raw cells plus a halo;
// NaN is written as the format's nodata value.
AssemblyStats AssembleRaster(const CellWindow& extent, int64_t halo_cells, const RawCellReader& read_raw,
                             const CellFinisher& finish, const RasterFormat& format, const RasterOutput& output);

}  // namespace sacfuse
