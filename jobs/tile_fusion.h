#pragma once
// Any fusion.method tile by tile (tiling.tile_size_m > 0): each tile loads only the windows of its views that its
// halo box needs (jobs/tile_view_source.h) and runs through FuseViews (jobs/fuse_views.h) like an untiled run,
// keeping only the points of its half-open core, so the tiles stitch into one cloud without seams or duplicates.
// MethodTileFuser is that step as the tile worker's injected TileFuser (tiles/tile_fuser.h); jobs/tiled_run.h and
// jobs/tile_queue.h run the tiles, each into its own LAS file.
#include <string>

#include "config/job_config.h"
#include "core/fusion_stats.h"
#include "core/point.h"
#include "core/sac_fusion.h"
#include "io/depth_block.h"
#include "io/view_identity.h"
#include "jobs/cluster_table_cache.h"
#include "jobs/fuse_views.h"
#include "tiles/tile_fuser.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

// Computes the superpixel and colour caches of every view (only the views of `only_tile` when given) that lacks a
// current one for the view's identity `inputs` (by view index; io/view_identity.h), logging why (nothing is read
// for the others); returns how many superpixel files were computed.
// `with_superpixels` false: the colour caches only (methods that do not read superpixels: FusionNeeds).
// `views_in_flight`: views prepared at once (jobs/view_batches.h; SuperpixelViewsInFlight).
size_t EnsureTiledSuperpixels(const DepthBlock& input, const TilePlan& plan, const SacOptions& options,
                              const std::string& superpixel_cache_dir, const std::vector<ViewIdentity>& inputs,
                              const SacProgress& progress = {},
                              const PlannedTile* only_tile = nullptr, bool with_superpixels = true,
                              size_t views_in_flight = 1);

// Runs fusion.method on one tile (which must have views) and writes the points of its core to `sink`. Needs the
// caches of EnsureTiledSuperpixels; reads only the tile's windows of them and of the depth maps. Cluster tables
// come from `cluster_cache` when given. The comparison methods compare views by the block's neighbour views and
// order (jobs/method_geometry.h) restricted to the tile. Throws InputError/Error on unreadable inputs.
FusedViews FuseTile(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile,
                    const FusionOptions& fusion, const std::string& superpixel_cache_dir, PointSink& sink,
                    ClusterTableCache* cluster_cache = nullptr);

// The fusion step of a job's tiles (fusion.method with the job's TSDF memory limit, superpixel caches and
// neighbour views), for the tile worker.
class MethodTileFuser : public TileFuser {
 public:
  // `cluster_cache` (may be null) is shared by the tiles; every reference must outlive the fuser.
  MethodTileFuser(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                  const std::vector<ViewIdentity>& identities, ClusterTableCache* cluster_cache = nullptr);
  uint64_t TileBytes(const PlannedTile& tile) const override;  // MethodTileBytes (jobs/method_memory.h)
  void PrepareTile(const PlannedTile& tile) override;          // EnsureTiledSuperpixels of the tile's views
  TileFused Fuse(const PlannedTile& tile, PointSink& sink) override;

 private:
  const JobConfig& config_;
  const DepthBlock& input_;
  const TilePlan& plan_;
  const std::vector<ViewIdentity>& identities_;
  ClusterTableCache* cluster_cache_;
  const FusionOptions fusion_;  // WithTsdfMemoryLimit(config)
  const std::string cache_dir_;  // SuperpixelCacheDir(config)
};

}  // namespace sacfuse
