#pragma once
// A tiled run of any fusion.method with per-tile outputs and resume (tiling.tile_size_m > 0; each tile through
// jobs/tile_fusion.h). State lives in DIR/tiles/:
//   run_config.yaml  the result-affecting settings of the last run (config/result_settings.h), to name changes
//   manifest.json    the tiles with views (grid order), the shared scale and offset, the settings hash
//   <id>.las / <id>.done.json / <id>.failed.json   see jobs/tile_marker.h
// Every tile LAS uses ONE scale (output.scale_m) and ONE offset: the project area's min corner (x, y) and the
// plan's z_min, each snapped down to a multiple of 1000 m, so tiles merge losslessly.
// Several workers (`sacfuse run` and `sacfuse tile` processes, on this or other machines sharing DIR) may work on
// one job: a tile is computed only under its claim (jobs/tile_claim.h); a run leaves tiles another live worker
// holds to it and waits for them (polling every second) before merging.
// Tiles run in parallel on up to resources.threads worker threads, each admitted only when its memory estimate
// fits next to the tiles already running (jobs/memory_admission.h); results do not depend on the thread count.
// A run (whose caller deleted leftover temporary files: jobs/run_state.h) skips tiles whose done marker verifies
// (settings, inputs, LAS file), computes the rest (a tile that throws gets a failed marker; the others go on),
// and, when every tile with views is done, merges the tile files in grid order into DIR/fused.las.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config/job_config.h"
#include "core/fusion_stats.h"
#include "core/sac_fusion.h"
#include "io/depth_block.h"
#include "io/las_writer.h"
#include "io/view_identity.h"
#include "jobs/tile_marker.h"
#include "jobs/output_layout.h"
#include "jobs/tile_plan.h"
#include "jobs/tile_fusion.h"

namespace sacfuse {

struct TiledRunOutcome {
  // Summed over the tiles computed by this invocation: emitted and the counters include each tile's halo work;
  // input counts the cores only; per-view vectors by the block's view index.
  FusionStats stats;
  size_t superpixels_computed = 0;  // superpixel files computed by the cache pass
  double superpixel_seconds = 0.0;  // the superpixel (and colour cache) pass
  size_t tiles_with_views = 0;
  size_t tiles_computed = 0;                                // this invocation (including failed attempts)
  size_t tiles_skipped = 0;                                 // verified done, not recomputed
  std::vector<std::string> tiles_rerun_for_inputs;          // recomputed because their views' inputs changed
  std::vector<std::pair<std::string, std::string>> failed;  // tile id, reason
  bool merged = false;                                      // DIR/fused.las written
  uint64_t merged_points = 0;
  std::vector<uint64_t> points_per_view;  // of the merged cloud, by view index
  double tiles_seconds = 0.0;             // wall time of the tile stage (all workers)
  double merge_seconds = 0.0;
};

// The shared offset of a plan's tiles (see above).
Eigen::Vector3d SharedTileOffset(const TilePlan& plan);
// Ids of the plan's tiles with views, grid order.
std::vector<std::string> TileIdsWithViews(const TilePlan& plan);

// Writes tiles/run_config.yaml (warning which result-affecting keys changed) and tiles/manifest.json.
// `las.offset` must be set.
void RecordTiledRunState(const JobConfig& config, const TilePlan& plan, const LasWriterOptions& las,
                         size_t tiles_to_compute);
// Computes one tile (the caller holds its claim) into <id>.las and <id>.done.json, after clearing its old state;
// logs "computing tile <id>". Needs the superpixel caches of the tile's views. Throws whatever the tile throws.
// `inputs` (TileInputsOf the tile) go into the done marker.
FusedViews ComputeTileFiles(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                            const PlannedTile& tile, const LasWriterOptions& las, const std::string& tiles_dir,
                            const std::string& hash, const TileInputs& inputs,
                            ClusterTableCache* cluster_cache = nullptr);

// Refuses a tile whose memory estimate exceeds what the budget leaves for tiles (the out-of-memory guard):
// throws Error naming the tile, the estimate and the keys to change.
void CheckTileFitsBudget(const PlannedTile& tile, const JobConfig& config);

// `rerun_ids` (already validated against TileIdsWithViews) are recomputed even when done; so is every tile whose
// recorded inputs differ from `identities` (the views' current ones; logged with the views that changed).
// fused_las_path is replaced (by a rename) only by a complete merge: a run that fails leaves the previous one.
TiledRunOutcome RunTiledJob(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                            const std::vector<ViewIdentity>& identities,
                            const std::vector<std::string>& rerun_ids, LasWriterOptions las_options,
                            const std::string& fused_las_path, const SacProgress& progress = {});

}  // namespace sacfuse
