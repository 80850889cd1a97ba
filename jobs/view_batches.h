#pragma once
// Reading and preparing views several at a time: an untiled run's loading and the tiled superpixel pass spend
// most of their time per view in one thread (decoding, SLIC of a view smaller than one superpixel block), so up to
// `in_flight` views are prepared at once. They flow through a pipeline, not batches: the next view starts as soon as
// one finishes, so no thread waits for the slowest view of a batch (issue 48: nadir and oblique views differ in
// cost). `in_flight` bounds the memory: at most that many views are being prepared at once, also when a view's own
// work is parallel. The results must not depend on the order in which the views finish (each view writes only its
// own slot).
#include <algorithm>
#include <cstddef>
#include <mutex>

#include <tbb/parallel_pipeline.h>

namespace sacfuse {

// Calls body(i) for every i in [0, count), at most `in_flight` (>= 1; 0 counts as 1) at once, started in index
// order, and after each body finished(n), n = the views finished so far (1, 2, ..., count), one call at a time
// (for progress reports). An exception thrown by a body reaches the caller.
template <typename Body, typename Finished>
void ForEachViewInFlight(size_t count, size_t in_flight, const Body& body, const Finished& finished) {
  std::mutex finished_mutex;
  size_t done = 0;
  size_t next = 0;
  tbb::parallel_pipeline(std::max<size_t>(1, in_flight),
                         tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order,
                                                        [&](tbb::flow_control& flow) {
                                                          if (next == count) flow.stop();
                                                          return next++;
                                                        }) &
                             tbb::make_filter<size_t, void>(tbb::filter_mode::parallel, [&](size_t i) {
                               body(i);
                               const std::lock_guard<std::mutex> lock(finished_mutex);
                               finished(++done);
                             }));
}

template <typename Body>
void ForEachViewInFlight(size_t count, size_t in_flight, const Body& body) {
  ForEachViewInFlight(count, in_flight, body, [](size_t) {});
}

}  // namespace sacfuse
