#include "jobs/view_batches.h"

#include <algorithm>

#include <tbb/task_arena.h>

#include "config/job_config.h"
#include "io/depth_block.h"
#include "tiles/memory_model.h"

namespace sacfuse {

size_t ViewsInFlight(const JobConfig& config, const DepthBlock& input, bool untiled) {
  const int threads = tbb::this_task_arena::max_concurrency();
  const BlockPixels pixels = MeasureBlockPixels(input);
  const uint64_t held = untiled ? UntiledSacBytes(pixels) : SuperpixelPassBytes(pixels);
  return SuperpixelViewsInFlight(pixels, MemoryBudgetBytes(config.resources.memory_gb),
                                 static_cast<size_t>(std::max(1, threads)), held);
}

}  // namespace sacfuse
