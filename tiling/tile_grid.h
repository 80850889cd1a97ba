#pragma once
// Geo-tiles: the project area cut into square tiles aligned to multiples of the tile size, each with a halo.
// A tile's CORE is half-open ([min, max) in x and y), so every XY belongs to exactly one tile; SAC runs on the
// HALO box (core grown by halo_m) so that points near a core border see the same neighbourhood as untiled, and
// only points inside the core are kept (seam-free stitching).
#include <optional>
#include <string>
#include <vector>

#include "core/owned_region.h"
#include "tiling/footprint.h"

namespace sacfuse {

struct TilingOptions {
  // Tile edge length, metres. 0 = automatic (jobs/auto_tiling.h): untiled when the whole block fits in the
  // memory budget, else the largest tiles of which resources.threads fit at once. A plan built with 0 has one
  // tile covering everything. >= 0.
  double tile_size_m = 0.0;
  double halo_m = 5.0;           // halo around each tile core, metres; >= 0
  int window_margin_px = 16;     // padding of each view's depth-raster window, depth pixels; >= 0
  // Height range of the block, metres, used only when the sparse model has no points (otherwise the 2nd..98th
  // percentile of the sparse points' z, padded by 10 m). z_max_m > z_min_m.
  double z_min_m = 0.0;
  double z_max_m = 100.0;
  // Multi-worker runs (tiles/tile_claim.h): a tile claim older than this is stale and may be taken over, seconds;
  // > 0. Not result-affecting.
  double claim_timeout_s = 6 * 3600.0;
};

// Throws ConfigError listing every broken rule as "TilingOptions.<field> = v: rule" (an invariant of tile planning;
// the YAML keys tiling.* are checked by config/option_table.cc).
void ValidateTilingOptions(const TilingOptions& options);

// Bounds of a tile grid, enforced where it is made (TileGrid's constructor): more tiles than this cannot be
// planned (each tile reads a halo and a depth window per view; 100,000 tiles of a city block are already tiles
// of a few metres), and a tile edge below kMinTileSizeGsd ground sampling distances is mostly halo.
constexpr double kMaxTiles = 100000;
constexpr double kMinTileSizeGsd = 10;

// Typical ground sampling distance of a block at height z_m, metres: the median over views of the distance along
// the principal ray to the plane z = z_m, divided by the focal length (views looking away from the plane are
// skipped). 0 when no view sees the plane.
double BlockGsdAtHeight(const std::vector<View>& views, double z_m);

struct TileIndex {
  int ix = 0, iy = 0;  // 0-based column (x) and row (y) in the grid
  bool operator==(const TileIndex& o) const { return ix == o.ix && iy == o.iy; }
  bool operator!=(const TileIndex& o) const { return !(*this == o); }
};

class TileGrid {
 public:
  // A grid covering `area` with tiles of tile_size_m aligned to multiples of it (tile_size_m = 0: one tile equal
  // to `area`). Throws Error for an empty area or a negative or non-finite size, and ConfigError naming
  // tiling.tile_size_m, its value, the area, the tile count and the limit when the grid would have more than
  // kMaxTiles tiles or (gsd_m > 0, the block's GSD) a tile edge below kMinTileSizeGsd x gsd_m.
  TileGrid(const Box2d& area, double tile_size_m, double halo_m, double gsd_m = 0.0);

  int num_x() const { return num_x_; }
  int num_y() const { return num_y_; }
  size_t size() const { return static_cast<size_t>(num_x_) * num_y_; }
  // Tiles in grid order: row by row (iy), then ix.
  std::vector<TileIndex> Tiles() const;
  const Box2d& area() const { return area_; }

  static std::string Id(const TileIndex& t);           // "ix_iy"
  std::optional<TileIndex> Parse(const std::string& id) const;  // nullopt for a malformed or unknown id

  // Half-open core [min, max): a point belongs to it when min <= p < max in x and y.
  Box2d CoreBounds(const TileIndex& t) const;
  Box2d HaloBounds(const TileIndex& t) const;  // core grown by halo_m on every side (closed box)
  bool CoreContains(const TileIndex& t, double x, double y) const;
  // The tile whose core holds (x, y); exactly one for any XY inside the grid. XY beyond the grid (points whose
  // depth lies outside the planning height range) belong to the nearest border tile (clamped), so no point is
  // ever lost or duplicated.
  TileIndex TileOf(double x, double y) const;
  // The points TileOf assigns to tile t, as a region: its core, open to infinity beyond the grid's outer edges.
  OwnedRegion OwnedRegionOf(const TileIndex& t) const;

 private:
  // Edge coordinate k (absolute multiple of tile size) along one axis; the single formula used everywhere.
  double Edge(long long k) const { return static_cast<double>(k) * tile_size_m_; }
  long long AxisIndex(double v, long long k0) const;

  Box2d area_;
  double tile_size_m_ = 0.0;
  double halo_m_ = 0.0;
  bool single_ = false;  // tile_size_m == 0
  long long kx0_ = 0, ky0_ = 0;  // absolute index of the first column / row
  int num_x_ = 1, num_y_ = 1;
};

}  // namespace sacfuse
