#pragma once
// Reading and preparing views several at a time: an untiled run's loading and the tiled superpixel pass spend
// most of their time per view in one thread (decoding, SLIC of a view smaller than one superpixel block), so views
// are taken `in_flight` at a time, each batch in parallel. Batches bound the memory: at most `in_flight` views are
// being prepared at once, also when a view's own work is parallel. The results must not depend on the order in
// which the views of a batch finish (each view writes only its own slot).
#include <algorithm>
#include <cstddef>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace sacfuse {

// Calls body(i) for every i in [0, count), at most `in_flight` (>= 1) at once, and after each body
// finished(n), n = the views finished so far (1, 2, ..., count), one call at a time (for progress reports).
template <typename Body, typename Finished>
void ForEachViewInBatches(size_t count, size_t in_flight, const Body& body, const Finished& finished) {
  const size_t batch = std::max<size_t>(1, in_flight);
  std::mutex finished_mutex;
  size_t done = 0;
  auto one = [&](size_t i) {
    body(i);
    const std::lock_guard<std::mutex> lock(finished_mutex);
    finished(++done);
  };
  for (size_t first = 0; first < count; first += batch) {
    const size_t last = std::min(count, first + batch);
    if (last - first == 1) {
      one(first);
    } else {
      tbb::parallel_for(
          tbb::blocked_range<size_t>(first, last, 1),
          [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) one(i);
          },
          tbb::simple_partitioner());
    }
  }
}

template <typename Body>
void ForEachViewInBatches(size_t count, size_t in_flight, const Body& body) {
  ForEachViewInBatches(count, in_flight, body, [](size_t) {});
}

}  // namespace sacfuse
