#pragma once
// One tile's work under its claim, the same for `sacfuse run` (jobs/tiled_run.h, many tiles on worker threads)
// and `sacfuse tile --id` (jobs/tile_queue.h, one tile per process): claim it (jobs/tile_claim.h), skip it when its
// done marker verifies, make the caches its views lack, check the memory guard, compute its LAS and done marker
// (jobs/tiled_run.h ComputeTileFiles), or write its failed marker.
#include <string>
#include <vector>

#include "config/job_config.h"
#include "io/depth_block.h"
#include "io/las_writer.h"
#include "io/view_identity.h"
#include "jobs/cluster_table_cache.h"
#include "jobs/fuse_views.h"
#include "jobs/memory_admission.h"
#include "jobs/tile_plan.h"

namespace sacfuse {

// What every tile of one run shares.
struct TileJob {
  const JobConfig& config;
  const DepthBlock& input;
  const TilePlan& plan;
  LasWriterOptions las;   // with the plan's shared offset
  std::string tiles_dir;  // DIR/tiles
  std::string hash;       // ResultSettingsHash(config)
  const std::vector<ViewIdentity>& identities;  // of every view (io/view_identity.h), by view index
  bool caches_ready = false;  // every view's superpixel and colour caches were made before the tiles (run)
};

enum class TileWork {
  kAlreadyDone,    // its done marker verifies: nothing to do
  kHeldElsewhere,  // another live worker holds its claim: nothing to do here
  kComputed,
  kFailed,         // <id>.failed.json written
};

struct TileWorkOutcome {
  TileWork result = TileWork::kAlreadyDone;
  std::string detail;  // kHeldElsewhere: the holder; kFailed: the reason
  FusedViews fused;    // kComputed
};

// Works on `tile` (which the caller found not done, or `forced`: recompute even when done) unless another live
// worker holds its claim or finished it meanwhile (checked again under the claim); makes the caches of its views
// unless job.caches_ready. A
// tile that throws gets a failed marker (the error is logged and returned, not thrown); claim I/O errors throw.
// `admission` (may be null) reserves the tile's memory estimate while it runs; `cluster_cache` may be null.
TileWorkOutcome WorkOnTile(const TileJob& job, const PlannedTile& tile, bool forced, MemoryAdmission* admission,
                           ClusterTableCache* cluster_cache);

}  // namespace sacfuse
