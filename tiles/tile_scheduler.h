#pragma once
// The tile stage of a tiled run (`sacfuse run`; jobs/tiled_run.h runs the stages): which tiles to compute, then
// those tiles on up to resources.threads TBB worker threads, each admitted only when its memory estimate fits
// next to the tiles already running (tiles/memory_admission.h); results do not depend on the thread count.
// Several workers (`sacfuse run` and `sacfuse tile` processes, on this or other machines sharing DIR) may work on
// one job: a tile is computed only under its claim (tiles/tile_claim.h); a run leaves tiles another live worker
// holds to it and waits for them (polling every second). Each tile runs through tiles/tile_worker.h with the
// injected fusion step (tiles/tile_fuser.h).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/fusion_stats.h"
#include "tiles/tile_fuser.h"
#include "tiles/tile_worker.h"

namespace sacfuse {

// Called as work proceeds: stage name, units done, units total.
using StageProgress = std::function<void(const std::string& stage, size_t done, size_t total)>;

struct TileWorkList {
  std::vector<const PlannedTile*> todo;      // to compute, grid order
  std::vector<std::string> forced;           // rerun requested: recomputed even when done
  size_t tiles_with_views = 0;
  size_t tiles_skipped = 0;                  // verified done, not recomputed
  std::vector<std::string> rerun_for_inputs;  // recomputed because their views' inputs changed
};

// Removes stale claims (when no live worker holds one) and sorts the tiles with views: `rerun_ids` (already
// validated) are recomputed even when done; so is every tile whose recorded inputs differ from job.identities
// (logged with the views that changed); tiles whose done marker verifies are skipped.
TileWorkList ListTileWork(const TileJob& job, const std::vector<std::string>& rerun_ids);

struct TileStageOutcome {
  // Summed over the tiles computed: emitted and the counters include each tile's halo work; input counts the
  // cores only; per-view vectors by the block's view index.
  FusionStats stats;
  size_t tiles_computed = 0;                                // including failed attempts
  std::vector<std::pair<std::string, std::string>> failed;  // tile id, reason; id order
  double seconds = 0.0;                                     // wall time of the stage
};

// Computes `work.todo` on min(threads, tiles) worker threads within the memory budget, then waits for the tiles
// other live workers hold (computing those whose worker died). Claim I/O errors end the stage after the workers
// stop and are rethrown.
TileStageOutcome RunTileWork(const TileJob& job, const TileWorkList& work, int threads, TileFuser& fuser,
                             const StageProgress& progress = {});

}  // namespace sacfuse
