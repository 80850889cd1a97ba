#pragma once
// Writing the DSM of an extent (core/dsm_rule.h's rule) from raw cell values, through the one assembly path of
// raster products (io/raster_assembly.h): the raw cells come from a cloud gridded in memory (`sacfuse dsm`, untiled
// runs) or from the raw window files of a tiled run's tiles; either way the same blocks are finished from the same
// raw cells, so the product does not depend on the tiling.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/cell_window.h"
#include "core/dsm_rule.h"
#include "io/cloud_grid.h"
#include "io/gdal_raster.h"
#include "io/point_cloud_file.h"
#include "io/raster_assembly.h"

namespace sacfuse {

constexpr double kDsmNodata = -9999.0;

// The DSM product: float32, nodata kDsmNodata, the CRS, overviews averaged, band "height (m)".
RasterFormat DsmRasterFormat(const std::string& crs_wkt);
// A tile's raw cells (tiles/<id>.dsm.tif): float32, NaN where a cell has no value.
RasterFormat DsmRawFormat(const std::string& crs_wkt);

struct DsmWriteStats {
  AssemblyStats assembly;
  DsmFinishStats finish;
  uint64_t raw_cells_with_value = 0;
  double seconds = 0.0;
};

// How the DSM grids a cloud: the rule's quantile and minimum points, at most max_points_in_memory points at once.
CloudGridOptions DsmCloudGridOptions(const DsmRule& rule, uint64_t max_points_in_memory);

// From the raw cells of `extent` (north-up, NaN = none).
DsmWriteStats WriteDsm(const std::vector<float>& raw, const CellWindow& extent, const DsmRule& rule,
                       const RasterFormat& format, const RasterOutput& output);
// Grids `cloud` over `extent` (io/cloud_grid.h, at most max_points_in_memory points at once) and writes its DSM;
// *grid (optional) receives the gridding's counts. Nothing is written when no point falls in the extent
// (grid->points_gridded == 0; the returned stats are empty).
DsmWriteStats WriteDsmOfCloud(PointCloudFile& cloud, const CellWindow& extent, const DsmRule& rule,
                              const RasterFormat& format, const RasterOutput& output, uint64_t max_points_in_memory,
                              CloudGrid* grid = nullptr);
// Raw values that replace the raw files' value of single cells, by global (col, row): a tiled run's cells that
// got points from more than one tile, recomputed from all of them (jobs/dsm_product.h). NaN = no value.
using RawCellPatch = std::map<std::pair<int64_t, int64_t>, float>;

// From raw window files (DsmRawFormat) covering parts of `extent`, with `patch` applied; cells neither covers have
// no value. Error when `raw_files` and `patch` are both empty.
DsmWriteStats WriteDsmFromRawFiles(const std::vector<std::string>& raw_files, const RawCellPatch& patch,
                                   const CellWindow& extent, const DsmRule& rule, const RasterFormat& format,
                                   const RasterOutput& output);

}  // namespace sacfuse
