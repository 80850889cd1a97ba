#pragma once
// The DSM of a run (output.dsm; docs/dsm-and-ortho.md): its grid, its per-tile raw windows and its assembly.
//   - The grid: cells of output.dsm_cell_m (0 = AutoDsmCell of the block's GSD, resolved by every process of the
//     run alike: `run`, `tile`, `merge`) on the global lattice (core/cell_window.h); the extent is the cells of the
//     project area (the tile plan's area, the same for tiled and untiled runs of a block) that meet the bounds of
//     the fused points.
//   - Tiled runs: each tile grids the points of its LAZ into its core's cells and keeps the points it fused beyond
//     its core (DsmTileProduct, a tiles/tile_product.h written before the tile's done marker); after the merge
//     the cells that got points from more than one tile are recomputed from all of them (their owner's LAZ is read
//     again for those cells only) and the raw windows are finished and assembled (AssembleTiledDsm): the DSM of
//     a tiled run is the DSM of its merged cloud, cell for cell.
//   - Untiled runs grid fused.las|laz once (MakeUntiledDsm).
//   - Either way io/dsm_file.h finishes the same raw cells block by block into DIR/dsm.tif (or DIR/dsm.vrt over
//     DIR/dsm/*.tif), so the DSM does not depend on the tiling.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/job_config.h"
#include "core/box2d.h"
#include "core/cell_window.h"
#include "core/dsm_rule.h"
#include "io/depth_block.h"
#include "io/dsm_file.h"
#include "tiles/tile_plan.h"
#include "tiles/tile_product.h"

namespace sacfuse {

// The automatic DSM cell: 2 x gsd_m rounded to the nearest of 1, 2, 2.5, 5 x 10^k (in log scale), the largest such
// value at most that which divides tile_size_m (> 0: a tiled run) into whole cells. Throws ConfigError when none
// from 1 mm up divides it.
double AutoDsmCell(double gsd_m, double tile_size_m);

// output.dsm_cell_m resolved: kept when given, else AutoDsmCell of the block's GSD (jobs/method_geometry.h
// BlockDepthGsd) for the tile size; 0 when the run writes no DSM.
double ResolveDsmCell(const JobConfig& config, const DepthBlock& input, double tile_size_m);

// The rule of output.dsm_* (the cell's quantile is fixed: core/dsm_rule.h's default, measured).
DsmRule DsmRuleOf(const OutputOptions& output);

// What a run's DSM is made on: its cells (ResolveDsmCell for config.tiling.tile_size_m, already resolved by
// jobs/auto_tiling.h) over the project area, its rule and CRS; nothing when the run writes no DSM.
struct DsmGrid {
  CellWindow extent;
  DsmRule rule;
  std::string crs_wkt;
  uint64_t max_points_in_memory = 0;  // gridding memory: a quarter of resources.memory_gb at 8 bytes a point
};
std::optional<DsmGrid> DsmGridOf(const JobConfig& config, const DepthBlock& input, const Box2d& project_area);

// What a tile makes for the DSM, from the points of its LAZ (read back, so the cells see exactly the delivered
// coordinates): the points whose cell lies in its core's cells are reduced to the raw values of those cells,
// DIR/tiles/<id>.dsm.tif (DsmRawFormat); the points it fused beyond its core (io/edge_points_file.h) go, as they
// are, to DIR/tiles/<id>.dsm_edge.bin. Either file is written only when it has something.
class DsmTileProduct : public TileProduct {
 public:
  static constexpr const char* kRawSuffix = "dsm.tif";
  static constexpr const char* kEdgeSuffix = "dsm_edge.bin";
  explicit DsmTileProduct(const DsmGrid& grid) : grid_(grid) {}
  std::vector<std::string> suffixes() const override { return {kRawSuffix, kEdgeSuffix}; }
  std::vector<std::string> Make(const PlannedTile& tile, const std::string& las_path,
                                const std::string& tiles_dir) const override;

 private:
  DsmGrid grid_;
};

struct DsmOutcome {
  bool written = false;
  std::string path;  // DIR/dsm.tif or DIR/dsm.vrt
  double cell_m = 0.0;
  int64_t cols = 0, rows = 0;
  uint64_t cells_with_value = 0;
  uint64_t raw_cells_with_value = 0;
  uint64_t cells_filled = 0;
  size_t files = 0;
  double seconds = 0.0;
};

// Finishes and writes DIR/dsm.tif (or .vrt) from the done tiles' raw windows (their done markers name them);
// removes the files of the other layout. A run whose tiles have no points writes no DSM (logged).
DsmOutcome AssembleTiledDsm(const JobConfig& config, const TilePlan& plan, const DsmGrid& grid);
// Grids `fused_las_path` over the grid and writes DIR/dsm.tif (or .vrt).
DsmOutcome MakeUntiledDsm(const JobConfig& config, const DsmGrid& grid, const std::string& fused_las_path);

// Removes a file or folder; absent is fine, failures are ignored (used for the other layout's files).
void RemoveQuietly(const std::string& path);
// Removes the files of a raster product an earlier run left (`product` names it in the log).
void RemoveEarlierRasterFiles(const std::string& product, const std::vector<std::string>& paths);
// Removes DIR/dsm.tif, DIR/dsm.vrt and DIR/dsm/ (a run that writes no DSM leaves none of an earlier run).
void RemoveDsmFiles(const JobConfig& config);

// The output of output.raster_layout for the DSM of `extent`.
RasterOutput DsmRasterOutput(const JobConfig& config, const CellWindow& extent);

}  // namespace sacfuse
