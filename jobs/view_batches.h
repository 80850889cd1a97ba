#pragma once
// Reading and preparing views several at a time: an untiled run's loading and the tiled superpixel pass spend
// most of their time per view in one thread (decoding, SLIC of a view smaller than one superpixel block), so views
// are taken `in_flight` at a time, each batch in parallel. Batches bound the memory: at most `in_flight` views are
// being prepared at once, also when a view's own work is parallel. The results must not depend on the order in
// which the views of a batch finish (each view writes only its own slot).
#include <algorithm>
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace sacfuse {

class DepthBlock;
struct JobConfig;

// Views a run prepares at once: one per thread of the run, as many as resources.memory_gb holds beside what the
// run holds meanwhile (tiles/memory_model.h SuperpixelViewsInFlight): the whole block's rasters in an untiled run
// (`untiled`), nothing but the process in the tiled superpixel pass.
size_t ViewsInFlight(const JobConfig& config, const DepthBlock& input, bool untiled);

// Calls body(i) for every i in [0, count), at most `in_flight` (>= 1) at once.
template <typename Body>
void ForEachViewInBatches(size_t count, size_t in_flight, const Body& body) {
  const size_t batch = std::max<size_t>(1, in_flight);
  for (size_t first = 0; first < count; first += batch) {
    const size_t last = std::min(count, first + batch);
    if (last - first == 1) {
      body(first);
    } else {
      tbb::parallel_for(
          tbb::blocked_range<size_t>(first, last, 1),
          [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) body(i);
          },
          tbb::simple_partitioner());
    }
  }
}

}  // namespace sacfuse
