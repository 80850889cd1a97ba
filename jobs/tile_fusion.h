#pragma once
// Any fusion.method tile by tile (tiling.tile_size_m > 0): each tile loads only the windows of its views that its
// halo box needs (jobs/tile_view_source.h) and runs through FuseViews (jobs/fuse_views.h) like an untiled run,
// keeping only the points of its half-open core, so the tiles stitch into one cloud without seams or duplicates.
// jobs/tiled_run.h runs the tiles, each into its own LAS file.
#include <string>

#include "config/job_config.h"
#include "core/fusion_stats.h"
#include "core/point.h"
#include "core/sac_fusion.h"
#include "io/depth_block.h"
#include "io/view_identity.h"
#include "jobs/cluster_table_cache.h"
#include "jobs/fuse_views.h"
#include "jobs/tile_plan.h"

namespace sacfuse {

// Computes the superpixel and colour caches of every view (only the views of `only_tile` when given) that lacks a
// current one for the view's identity `inputs` (by view index; io/view_identity.h), logging why (nothing is read
// for the others); returns how many superpixel files were computed.
// `with_superpixels` false: the colour caches only (methods that do not read superpixels: FusionNeeds).
size_t EnsureTiledSuperpixels(const DepthBlock& input, const TilePlan& plan, const SacOptions& options,
                              const std::string& superpixel_cache_dir, const std::vector<ViewIdentity>& inputs,
                              const SacProgress& progress = {},
                              const PlannedTile* only_tile = nullptr, bool with_superpixels = true);

// Runs fusion.method on one tile (which must have views) and writes the points of its core to `sink`. Needs the
// caches of EnsureTiledSuperpixels; reads only the tile's windows of them and of the depth maps. Cluster tables
// come from `cluster_cache` when given. The comparison methods compare views by the block's neighbour views and
// order (jobs/method_geometry.h) restricted to the tile. Throws InputError/Error on unreadable inputs.
FusedViews FuseTile(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile,
                    const FusionOptions& fusion, const std::string& superpixel_cache_dir, PointSink& sink,
                    ClusterTableCache* cluster_cache = nullptr);

}  // namespace sacfuse
