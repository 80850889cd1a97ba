#pragma once
// SAC tile by tile (tiling.tile_size_m > 0): each tile loads only the windows of its views' depth maps,
// superpixel labels and colours that its halo box needs, runs core's RunSacFusion on them, and keeps only the
// points whose XY lies in the tile's half-open core, so the tiles stitch into one cloud without seams or
// duplicates. jobs/tiled_run.h runs the tiles one after another, each into its own LAS file.
// The other methods (fusion.method union | consistency | disparity_normal | tsdf | multiray) run through the same
// tiles, windows and core filter, reading depth and colour windows only (no superpixels are computed for them).
#include <string>

#include "core/point.h"
#include "config/job_config.h"
#include "core/method_stats.h"
#include "core/sac_fusion.h"
#include "io/depth_block.h"
#include "jobs/cluster_table_cache.h"
#include "jobs/sac_block.h"
#include "jobs/tile_plan.h"

namespace sacfuse {

// Computes the superpixel and colour caches of every view (only the views of `only_tile` when given) that lacks a current one
// (nothing is read for the others); returns how many were computed. `with_superpixels` false: the colour caches
// only (methods without superpixels: see MethodUsesSuperpixels in jobs/fusion_methods.h).
size_t EnsureTiledSuperpixels(const DepthBlock& input, const TilePlan& plan, const SacOptions& options,
                              const std::string& superpixel_cache_dir, const SacProgress& progress = {},
                              const PlannedTile* only_tile = nullptr, bool with_superpixels = true);

struct TileFusionResult {
  SacStats stats;                    // sac: of the tile's halo (emitted_per_view indexed like tile.views)
  MethodStats method_stats;          // other methods: of the tile's halo (emitted_per_view indexed like tile.views)
  uint64_t points_in_core = 0;       // written to the sink
  uint64_t points_outside_core = 0;  // in the halo, left to the neighbouring tiles (SAC: valid pixels whose own
                                     // point lies there; other methods: points emitted there)
};

// Runs fusion.method on one tile (which must have views) and writes the points of its core to `sink`. Needs the
// superpixel (sac) and colour caches (EnsureTiledSuperpixels); reads only the tile's windows of them and of the
// depth maps. Cluster tables come from `cluster_cache` when given. Methods other than sac compare views by the
// block's neighbour views and order (jobs/method_geometry.h) restricted to the tile. Throws InputError/Error on
// unreadable inputs.
TileFusionResult FuseTile(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile,
                          const FusionOptions& fusion, const std::string& superpixel_cache_dir, PointSink& sink,
                          ClusterTableCache* cluster_cache = nullptr);

// Adds one tile's stats to a running total (mean_correspondences is summed weighted by valid nodes: divide by
// total->valid_nodes at the end; emitted_per_view is not touched).
void AddSacStats(const SacStats& tile, SacStats* total);

}  // namespace sacfuse
