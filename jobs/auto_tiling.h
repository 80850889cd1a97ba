#pragma once
// `tiling.tile_size_m: 0` (the default) sizes tiles from the memory budget: a block whose untiled SAC fits in
// `resources.memory_gb` runs untiled (fastest, no halos); otherwise it runs in the largest square tiles of which
// `resources.threads` fit in the budget at once. A run in progress keeps its tile size (so a resumed run or a
// worker on a machine with another budget computes the same tiles).
#include <cstdint>
#include <string>

#include "config/job_config.h"
#include "io/depth_block.h"

namespace sacfuse {

struct TilingDecision {
  bool tiled = false;
  double tile_size_m = 0.0;      // > 0 when tiled
  bool automatic = false;        // chosen here (tiling.tile_size_m was 0)
  uint64_t budget_bytes = 0;
  uint64_t untiled_bytes = 0;    // estimate of untiled SAC
  uint64_t max_tile_bytes = 0;   // estimate of the largest tile (tiled)
  int parallel_tiles = 1;        // tiles that fit in the budget at once (<= threads)
  // Views the untiled load or the tiled superpixel pass prepares at once (jobs/view_batches.h): one per thread, as
  // many as the budget holds beside the run's estimate (tiles/memory_model.h SuperpixelViewsInFlight).
  size_t views_in_flight = 1;
  std::string reason;            // one line for the log
};

// Worker threads of resources.threads (0 = all cores), at least 1.
int EffectiveThreads(const JobConfig& config);

// Decides untiled vs tiled and the tile size. Explicit tile sizes are kept (tiled when > 0, for every method);
// without one the union method runs untiled, the others are sized like SAC. Throws ConfigError when even small
// tiles exceed the budget, or when dense correspondences (untiled only) do not fit.
TilingDecision DecideTiling(const JobConfig& config, const DepthBlock& input);

// `config` with tiling.tile_size_m set to the decision (0 = untiled). Logs the decision once.
JobConfig ResolveTiling(const JobConfig& config, const DepthBlock& input, TilingDecision* decision = nullptr);

}  // namespace sacfuse
