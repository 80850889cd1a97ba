#include "jobs/dsm_product.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "config/output_layout.h"
#include "core/cell_heights.h"
#include "core/error.h"
#include "io/cloud_grid.h"
#include "io/crs_wkt.h"
#include "io/edge_points_file.h"
#include "io/gdal_raster.h"
#include "io/point_cloud_file.h"
#include "jobs/method_geometry.h"
#include "tiles/memory_model.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

constexpr double kAutoCellGsd = 2.0;  // the automatic DSM cell, in GSDs (docs/dsm-and-ortho.md: measured)

// 1, 2, 2.5, 5 x 10^k from the largest at most `v` down to 1 mm.
std::vector<double> NiceValuesDownFrom(double v) {
  std::vector<double> out;
  for (int k = static_cast<int>(std::floor(std::log10(v))) + 1; k >= -3; --k) {
    for (const double m : {5.0, 2.5, 2.0, 1.0}) {
      const double x = m * std::pow(10.0, k);
      if (x <= v * (1 + 1e-9) && x >= 1e-3 * (1 - 1e-9)) out.push_back(x);
    }
  }
  return out;
}

// The nice value nearest to v in log scale.
double NearestNice(double v) {
  double best = 1.0, best_d = 1e300;
  const int k0 = static_cast<int>(std::floor(std::log10(v)));
  for (int k = k0 - 1; k <= k0 + 1; ++k) {
    for (const double m : {1.0, 2.0, 2.5, 5.0}) {
      const double x = m * std::pow(10.0, k);
      const double d = std::abs(std::log(x / v));
      if (d < best_d) best = x, best_d = d;
    }
  }
  return best;
}

// The DSM's extent: the cells of the project area that meet the bounds of the points (so the raster does not
// carry the empty margin of the views' footprints).
CellWindow ExtentOfPoints(const DsmGrid& grid, const Box2d& points) {
  return grid.extent.Intersection(CellWindowCovering(points, grid.extent.cell_m));
}

DsmOutcome OutcomeOf(const CellWindow& extent, const DsmWriteStats& s) {
  DsmOutcome o;
  o.written = true;
  o.path = s.assembly.files.front();
  o.cell_m = extent.cell_m;
  o.cols = extent.cols;
  o.rows = extent.rows;
  o.cells_with_value = s.assembly.cells_with_value;
  o.raw_cells_with_value = s.raw_cells_with_value;
  o.cells_filled = s.finish.cells_filled;
  o.files = s.assembly.files.size();
  o.seconds = s.seconds;
  spdlog::info("dsm: {} ({} x {} cells of {} m, {:.1f} % with a value: {} from points, {} in filled holes) in {:.1f} s",
               o.path, o.cols, o.rows, o.cell_m, o.cells_with_value * 100.0 / std::max<double>(1, o.cols * o.rows),
               o.raw_cells_with_value, o.cells_filled, o.seconds);
  return o;
}

// Removes the files of the layout not written now (a run switching layouts leaves no stale DSM beside the new).
void RemoveOtherLayout(const JobConfig& config, const RasterOutput& output) {
  if (output.blocks) {
    RemoveQuietly(DsmPath(config));
  } else {
    RemoveQuietly(DsmVrtPath(config));
    RemoveQuietly(DsmBlocksDir(config));
  }
}

// The cells that got points from more than one tile (a tile's points fused beyond its core, its edge file, fall in
// its neighbours' cells), each recomputed from all of its points: the edge points plus the points of the tile
// owning the cell, read again from its LAZ (one pass per owning tile, keeping only those cells' heights).
RawCellPatch SharedCellPatch(const std::string& tiles_dir, const TilePlan& plan, const DsmGrid& grid,
                             const std::vector<std::string>& edge_files) {
  const double cell = grid.extent.cell_m;
  std::map<std::pair<int64_t, int64_t>, std::vector<float>> heights;  // by (col, row)
  for (const std::string& path : edge_files) {
    for (const Eigen::Vector3d& p : ReadEdgePointsFile(path)) {
      const int64_t col = CellIndexOf(p.x(), cell), row = CellIndexOf(p.y(), cell);
      if (grid.extent.Contains(col, row)) heights[{col, row}].push_back(static_cast<float>(p.z()));
    }
  }
  std::set<std::string> owners;
  for (const auto& entry : heights) {
    const auto& [col, row] = entry.first;
    owners.insert(TileGrid::Id(plan.grid.TileOf(CellEdge(col, cell) + 0.5 * cell, CellEdge(row, cell) + 0.5 * cell)));
  }
  std::vector<const PlannedTile*> owner_tiles;
  for (const PlannedTile& tile : plan.tiles) {
    if (owners.count(tile.id)) owner_tiles.push_back(&tile);
  }
  // The owners' passes run on the job's threads: each owner adds only to the cells of its core, which no other
  // owner holds (a cell's heights are sorted before their quantile is taken: their order does not matter).
  tbb::parallel_for(size_t{0}, owner_tiles.size(), [&](size_t t) {
    const PlannedTile& tile = *owner_tiles[t];
    const auto marker = ReadTileDoneMarker(tiles_dir, tile.id);
    if (!marker || marker->points == 0) return;
    const CellWindow core = CellWindowOfHalfOpen(tile.core, cell).Intersection(grid.extent);
    PointCloudFile cloud(TileCloudPath(tiles_dir, *marker));
    CloudChunk chunk;
    while (cloud.Read(&chunk, kCloudReadChunkPoints) > 0) {
      for (const Eigen::Vector3d& p : chunk.xyz) {
        if (!p.allFinite()) continue;
        const int64_t col = CellIndexOf(p.x(), cell), row = CellIndexOf(p.y(), cell);
        if (!core.Contains(col, row)) continue;
        const auto it = heights.find({col, row});  // the map's shape does not change here: finds are safe
        if (it != heights.end()) it->second.push_back(static_cast<float>(p.z()));
      }
    }
  });
  std::vector<std::pair<const std::pair<int64_t, int64_t>, std::vector<float>>*> cells;
  for (auto& entry : heights) cells.push_back(&entry);
  std::vector<float> values(cells.size());
  tbb::parallel_for(size_t{0}, cells.size(), [&](size_t i) {
    values[i] = CellValueOf(&cells[i]->second, grid.rule.quantile, grid.rule.min_points);
  });
  RawCellPatch patch;
  for (size_t i = 0; i < cells.size(); ++i) patch.emplace_hint(patch.end(), cells[i]->first, values[i]);
  spdlog::info("dsm: {} cells got points from two tiles or more (recomputed from {} tiles' points)", patch.size(),
               owners.size());
  return patch;
}

}  // namespace

double AutoDsmCell(double gsd_m, double tile_size_m) {
  const double target = NearestNice(kAutoCellGsd * gsd_m);
  if (tile_size_m <= 0) return target;
  for (const double cell : NiceValuesDownFrom(target)) {
    if (IsWholeNumberOfCells(tile_size_m, cell)) return cell;
  }
  throw ConfigError("output.dsm_cell_m = 0 (automatic): no cell from " + std::to_string(target) +
                    " m down to 1 mm divides tiling.tile_size_m = " + std::to_string(tile_size_m) +
                    " into whole cells; give output.dsm_cell_m");
}

double ResolveDsmCell(const JobConfig& config, const DepthBlock& input, double tile_size_m) {
  if (!DsmWanted(config)) return 0.0;
  if (config.output.dsm_cell_m > 0) return config.output.dsm_cell_m;
  std::vector<DepthRasterSize> sizes;
  for (const View& view : input.views()) sizes.push_back(input.DepthSize(view));
  double z_min = 0, z_max = 0;
  std::string source;
  BlockHeightRange(input, config.tiling, &z_min, &z_max, &source);
  const double gsd = BlockDepthGsd(input, sizes, z_min, z_max);
  if (!(gsd > 0)) {
    throw ConfigError("output.dsm_cell_m = 0 (automatic): no view looks down on the block, so its GSD is unknown; "
                      "give output.dsm_cell_m");
  }
  const double cell = AutoDsmCell(gsd, tile_size_m);
  spdlog::info("dsm: cell {} m (2 x the block's GSD of {:.3f} m, rounded{})", cell, gsd,
               tile_size_m > 0 ? fmt::format("; divides the {} m tiles", tile_size_m) : std::string());
  return cell;
}

DsmRule DsmRuleOf(const OutputOptions& output) {
  DsmRule rule;
  rule.max_hole_m = output.dsm_max_hole_m;
  return rule;
}

std::optional<DsmGrid> DsmGridOf(const JobConfig& config, const DepthBlock& input, const Box2d& project_area) {
  if (!DsmWanted(config)) return std::nullopt;
  DsmGrid grid;
  grid.extent = CellWindowCovering(project_area, ResolveDsmCell(config, input, config.tiling.tile_size_m));
  grid.rule = DsmRuleOf(config.output);
  grid.crs_wkt = ProjectCrsWkt(config.crs, CrsWktDialect::kGdal);
  grid.max_points_in_memory = MemoryBudgetBytes(config.resources.memory_gb) / 4 / 8;
  return grid;
}

std::vector<std::string> DsmTileProduct::Make(const PlannedTile& tile, const std::string& las_path,
                                              const std::string& tiles_dir) const {
  if (las_path.empty()) return {};
  const CellWindow core = CellWindowOfHalfOpen(tile.core, grid_.extent.cell_m).Intersection(grid_.extent);
  CellHeights heights(core);
  std::vector<Eigen::Vector3d> edge;  // fused beyond the core, inside the DSM's extent
  PointCloudFile cloud(las_path);
  CloudChunk chunk;
  while (cloud.Read(&chunk, kCloudReadChunkPoints) > 0) {
    for (const Eigen::Vector3d& p : chunk.xyz) {
      if (!p.allFinite()) continue;
      const int64_t col = CellIndexOf(p.x(), grid_.extent.cell_m), row = CellIndexOf(p.y(), grid_.extent.cell_m);
      if (core.Contains(col, row)) {
        heights.AddToCell(col, row, p.z());
      } else if (grid_.extent.Contains(col, row)) {
        edge.push_back(p);
      }
    }
  }
  std::vector<std::string> written;
  if (heights.points() > 0) {
    const std::vector<float> raw = heights.Reduce(grid_.rule.quantile, grid_.rule.min_points);
    WriteRasterFile(TileProductPath(tiles_dir, tile.id, kRawSuffix), core, DsmRawFormat(grid_.crs_wkt), raw.data(),
                    RasterLayout::kIntermediate);
    written.push_back(kRawSuffix);
  }
  if (!edge.empty()) {
    WriteEdgePointsFile(TileProductPath(tiles_dir, tile.id, kEdgeSuffix), edge);
    written.push_back(kEdgeSuffix);
  }
  return written;
}

void RemoveQuietly(const std::string& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
}

void RemoveEarlierRasterFiles(const std::string& product, const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    std::error_code ec;
    if (fs::exists(path, ec)) {
      spdlog::info("{}: removing {} of an earlier run", product, path);
      RemoveQuietly(path);
    }
  }
}

void RemoveDsmFiles(const JobConfig& config) {
  RemoveEarlierRasterFiles("dsm", {DsmPath(config), DsmVrtPath(config), DsmBlocksDir(config)});
}

RasterOutput DsmRasterOutput(const JobConfig& config, const CellWindow& extent) {
  RasterOutput out;
  out.blocks = RasterLayoutIsBlocks(config.output.raster_layout, extent);
  out.single_path = DsmPath(config);
  out.blocks_dir = DsmBlocksDir(config);
  out.vrt_path = DsmVrtPath(config);
  return out;
}

DsmOutcome AssembleTiledDsm(const JobConfig& config, const TilePlan& plan, const DsmGrid& grid) {
  const std::string tiles_dir = TilesDir(config);
  std::vector<std::string> raw_files, edge_files;
  Box2d points;  // the XY bounds of the tiles' points: the DSM's extent within the project area
  for (const std::string& id : TileIdsWithViews(plan)) {
    const auto marker = ReadTileDoneMarker(tiles_dir, id);
    if (!marker) throw Error(TileDonePath(tiles_dir, id) + ": done marker vanished before the DSM was assembled");
    for (const TileProductFile& p : marker->products) {
      if (p.suffix == DsmTileProduct::kRawSuffix) raw_files.push_back(TileProductPath(tiles_dir, id, p.suffix));
      if (p.suffix == DsmTileProduct::kEdgeSuffix) edge_files.push_back(TileProductPath(tiles_dir, id, p.suffix));
    }
    if (marker->points > 0) points.Extend(Box2d(marker->min[0], marker->min[1], marker->max[0], marker->max[1]));
  }
  const CellWindow extent = ExtentOfPoints(grid, points);
  const RasterOutput output = DsmRasterOutput(config, extent);
  RemoveOtherLayout(config, output);
  if (raw_files.empty() && edge_files.empty()) {
    spdlog::warn("dsm: no tile has points in the DSM's extent; no DSM written");
    RemoveDsmFiles(config);
    return {};
  }
  const RawCellPatch patch = SharedCellPatch(tiles_dir, plan, grid, edge_files);
  return OutcomeOf(extent,
                   WriteDsmFromRawFiles(raw_files, patch, extent, grid.rule, DsmRasterFormat(grid.crs_wkt), output));
}

DsmOutcome MakeUntiledDsm(const JobConfig& config, const DsmGrid& grid, const std::string& fused_las_path) {
  PointCloudFile cloud(fused_las_path);
  const CellWindow extent = ExtentOfPoints(grid, cloud.bounds_xy());
  const RasterOutput output = DsmRasterOutput(config, extent);
  RemoveOtherLayout(config, output);
  CloudGrid raw;
  DsmWriteStats stats;
  if (!extent.empty()) {
    stats = WriteDsmOfCloud(cloud, extent, grid.rule, DsmRasterFormat(grid.crs_wkt), output, grid.max_points_in_memory,
                            &raw);
  }
  if (raw.points_gridded == 0) {
    spdlog::warn("dsm: {} has no points in the DSM's extent; no DSM written", fused_las_path);
    RemoveDsmFiles(config);
    return {};
  }
  return OutcomeOf(extent, stats);
}

}  // namespace sacfuse
