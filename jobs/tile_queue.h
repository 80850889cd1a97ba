#pragma once
// The tile list of a tiled run as a work queue for several processes or machines sharing DIR:
//   `sacfuse plan CONFIG --list`   PlanJob: the tile ids with views (SharedTilePlan, tiles/tile_plan.h)
//   `sacfuse tile CONFIG --id ID`  RunOneTile: computes exactly one tile under its claim (tiles/tile_claim.h)
//   `sacfuse merge CONFIG`         MergeJob: merges once every tile with views is done (tiles/tile_merge.h), then
//                                  assembles the DSM (jobs/dsm_product.h)
// and `sacfuse run` (jobs/tiled_run.h) honours the same claims, so all of them can be mixed.
#include <string>
#include <vector>

#include "config/job_config.h"
#include "jobs/dsm_product.h"
#include "jobs/ortho_product.h"
#include "jobs/output_lock.h"
#include "tiles/tile_merge.h"
#include "tiles/tile_plan.h"
#include "tiles/tile_worker.h"

namespace sacfuse {

// `sacfuse plan`: validates the config, opens the workspace, resolves an automatic tile size (a block that runs
// untiled gets the one-tile plan) and returns SharedTilePlan.
TilePlan PlanJob(const JobConfig& config, std::string* plan_path = nullptr);

// Computes tile `id` (a tile with views of the shared plan, else ConfigError) unless it is done or claimed by a
// live worker (tiles/tile_worker.h); the claim is removed when the tile is done or failed. DIR/fused.las stays
// (the previous merge) until `sacfuse merge` replaces it. The caller holds the workers' shared lock; temporary
// files of gone processes on this host are removed first, and a worker whose config hash or inputs differ from
// those of a run or merge writing DIR refuses (Error; jobs/output_lock.h CheckWorkerMatchesWriter).
TileWorkOutcome RunOneTile(const JobConfig& config, const std::string& id, const OutputWorkerLock& lock);

struct MergeJobOutcome {
  std::vector<std::string> missing;  // not empty: nothing was merged
  std::string fused_las_path;
  MergeResult merged;
  DsmOutcome dsm;  // output.dsm: the DSM assembled from the tiles (jobs/dsm_product.h)
  OrthoOutcome ortho;  // output.ortho: the true orthophoto on the DSM (jobs/ortho_product.h)
};

// `sacfuse merge`: ConfigError unless the config is a tiled run. The caller holds the writer lock (recorded with
// the job's hash and inputs digest); temporary files (and COPC work folders) of gone processes are removed first;
// the other formats' clouds of an earlier run are removed after the merge.
MergeJobOutcome MergeJob(const JobConfig& config, OutputWriterLock& lock);

}  // namespace sacfuse
