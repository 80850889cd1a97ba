#pragma once
// A tiled run of any fusion.method with per-tile outputs and resume (tiling.tile_size_m > 0), in stages:
//   1. which tiles to compute (tiles/tile_scheduler.h ListTileWork: done tiles whose marker verifies are
//      skipped, tiles whose inputs changed or that were asked for are recomputed) and the run's state in DIR/tiles
//      (tiles/tile_manifest.h: manifest.json, run_config.yaml);
//   2. the superpixel and colour caches of every view (jobs/tile_fusion.h EnsureTiledSuperpixels);
//   3. the tiles on worker threads within the memory budget (tiles/tile_scheduler.h RunTileWork), each through
//      the tile worker (tiles/tile_worker.h) with this job's fusion step (jobs/tile_fusion.h MethodTileFuser); a
//      tile that throws gets a failed marker and the others go on;
//   4. when every tile with views is done and no input file changed since the run started, the tile files merged
//      in grid order into DIR/fused.las (tiles/tile_merge.h: every tile's marker checked against this job), and the
//      tiles' DSM files assembled into DIR/dsm.tif (jobs/dsm_product.h).
// The caller deleted leftover temporary files first (jobs/run_state.h).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config/job_config.h"
#include "core/fusion_stats.h"
#include "io/depth_block.h"
#include "io/las_writer.h"
#include "io/stage_clock.h"
#include "io/view_identity.h"
#include "jobs/dsm_product.h"
#include "jobs/ortho_product.h"
#include "tiles/tile_plan.h"
#include "tiles/tile_scheduler.h"

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
  DsmOutcome dsm;                         // the DSM assembled after the merge (output.dsm)
  OrthoOutcome ortho;                     // the true orthophoto made on it (output.ortho)
};

// `rerun_ids` (already validated against TileIdsWithViews) are recomputed even when done; so is every tile whose
// recorded inputs differ from `identities` (the views' current ones; logged with the views that changed).
// fused_las_path is replaced (by a rename) only by a complete merge: a run that fails leaves the previous one.
// Every cloud is written with jobs/las_options.h (tiles: TileCloudOptions; the merged cloud: FusedCloudOptions).
// `views_in_flight`: views the superpixel pass prepares at once (TilingDecision::views_in_flight). `pinned` (may be
// null): the views' files when the run started; one that changed since fails the run before the merge (InputError
// naming it, io/view_identity.h CheckInputsUnchanged).
// `clock` (optional): marks the stages "tile plan" (stage 1), "superpixels", "tiles" and "merge" as they end.
TiledRunOutcome RunTiledJob(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                            const std::vector<ViewIdentity>& identities,
                            const std::vector<std::string>& rerun_ids, const std::string& fused_las_path,
                            const StageProgress& progress = {}, size_t views_in_flight = 1,
                            const std::vector<ViewIdentity>* pinned = nullptr, StageClock* clock = nullptr);

}  // namespace sacfuse
