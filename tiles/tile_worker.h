#pragma once
// One tile's work under its claim, the same for `sacfuse run` (tiles/tile_scheduler.h, many tiles on worker
// threads) and `sacfuse tile --id` (jobs/tile_queue.h, one tile per process): claim it (tiles/tile_claim.h), skip it
// when its done marker verifies, make the caches its views lack, check the memory guard, fuse it into its point
// file (<id>.laz, or <id>.copc.laz for COPC) through the injected TileFuser (tiles/tile_fuser.h) and write its done marker (tiles/tile_marker.h), or write
// its failed marker.
#include <string>
#include <vector>

#include "config/job_config.h"
#include "io/depth_block.h"
#include "io/point_cloud_writer.h"
#include "io/view_identity.h"
#include "tiles/memory_admission.h"
#include "tiles/tile_fuser.h"
#include "tiles/tile_marker.h"
#include "tiles/tile_plan.h"
#include "tiles/tile_product.h"

namespace sacfuse {

// What every tile of one run shares.
struct TileJob {
  const JobConfig& config;
  const DepthBlock& input;
  const TilePlan& plan;
  CloudFileOptions cloud;  // with the plan's shared offset; copc set: the tiles are COPC
  std::string tiles_dir;  // DIR/tiles
  std::string hash;       // ResultSettingsHash(config)
  const std::vector<ViewIdentity>& identities;  // of every view (io/view_identity.h), by view index
  bool caches_ready = false;  // every view's superpixel and colour caches were made before the tiles (run)
  // Files each tile makes beside its points, covered by its done marker (tiles/tile_product.h); not owned.
  std::vector<const TileProduct*> products;
};

// The file suffixes of a job's products.
std::vector<std::string> ProductSuffixes(const TileJob& job);

enum class TileWork {
  kAlreadyDone,    // its done marker verifies: nothing to do
  kHeldElsewhere,  // another live worker holds its claim: nothing to do here
  kComputed,
  kFailed,         // <id>.failed.json written
};

struct TileWorkOutcome {
  TileWork result = TileWork::kAlreadyDone;
  std::string detail;  // kHeldElsewhere: the holder; kFailed: the reason
  TileFused fused;     // kComputed
};

// Works on `tile` (which the caller found not done, or `forced`: recompute even when done) unless another live
// worker holds its claim or finished it meanwhile (checked again under the claim); makes the caches of its views
// (fuser.PrepareTile) unless job.caches_ready. A tile that throws gets a failed marker (the error is logged and
// returned, not thrown); claim I/O errors throw. `admission` (may be null) reserves the tile's memory estimate
// (fuser.TileBytes) while it runs.
TileWorkOutcome WorkOnTile(const TileJob& job, const PlannedTile& tile, bool forced, MemoryAdmission* admission,
                           TileFuser& fuser);

// Computes one tile (the caller holds its claim) into its point file, its product files and <id>.done.json, after
// clearing its old state;
// logs "computing tile <id>". Throws whatever the tile throws. `inputs` (TileInputsOf the tile) go into the done
// marker.
TileFused ComputeTileFiles(const TileJob& job, const PlannedTile& tile, const TileInputs& inputs, TileFuser& fuser);

// Refuses a tile whose memory estimate `bytes` exceeds what the budget leaves for tiles (the out-of-memory
// guard): throws Error naming the tile, the estimate and the keys to change.
void CheckTileFitsBudget(const PlannedTile& tile, uint64_t bytes, const JobConfig& config);

}  // namespace sacfuse
