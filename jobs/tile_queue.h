#pragma once
// The tile list of a tiled run as a work queue for several processes or machines sharing DIR:
//   `sacfuse plan CONFIG --list`   the tile ids with views (SharedTilePlan, jobs/tile_plan.h)
//   `sacfuse tile CONFIG --id ID`  RunOneTile: computes exactly one tile under its claim (jobs/tile_claim.h)
//   `sacfuse merge CONFIG`         MergeJob: merges once every tile with views is done
// and `sacfuse run` (jobs/tiled_run.h) honours the same claims, so all of them can be mixed.
#include <cstdint>
#include <string>
#include <vector>

#include "config/job_config.h"
#include "io/las_writer.h"
#include "io/view_identity.h"
#include "core/sac_fusion.h"
#include "jobs/tile_merge.h"
#include "jobs/tile_plan.h"
#include "jobs/tile_worker.h"

namespace sacfuse {

// Computes tile `id` (a tile with views of the shared plan, else ConfigError) unless it is done or claimed by a
// live worker (jobs/tile_worker.h); the claim is removed when the tile is done or failed. DIR/fused.las stays
// (the previous merge) until `sacfuse merge` replaces it.
TileWorkOutcome RunOneTile(const JobConfig& config, const std::string& id);

// Tiles with views whose done marker does not verify (full checksum, and inputs against `identities`, by view
// index), grid order.
std::vector<std::string> MissingTiles(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                                      const std::vector<ViewIdentity>& identities);

// Streams the done tiles' LAS files, grid order, into `fused_las_path`; `las.offset` must be the plan's shared
// offset. Throws Error when a tile with views has no done marker.
MergeResult MergeTiledRun(const JobConfig& config, const TilePlan& plan, const LasWriterOptions& las,
                          const std::string& fused_las_path, const SacProgress& progress = {});

struct MergeJobOutcome {
  std::vector<std::string> missing;  // not empty: nothing was merged
  std::string fused_las_path;
  MergeResult merged;
};

// `sacfuse merge`: ConfigError unless the config is a tiled SAC run.
MergeJobOutcome MergeJob(const JobConfig& config);

}  // namespace sacfuse
