#include "jobs/view_batches.h"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

// Every index once, never more than `in_flight` at once.
void CheckBatches(size_t count, size_t in_flight) {
  std::vector<std::atomic<int>> calls(count);
  std::atomic<int> running{0}, most{0};
  std::vector<size_t> finished;
  ForEachViewInBatches(count, in_flight, [&](size_t i) {
    const int now = ++running;
    int seen = most.load();
    while (now > seen && !most.compare_exchange_weak(seen, now)) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ++calls[i];
    --running;
  }, [&](size_t n) { finished.push_back(n); });
  for (size_t i = 0; i < count; ++i) EXPECT_EQ(calls[i].load(), 1) << "index " << i;
  EXPECT_LE(most.load(), static_cast<int>(std::max<size_t>(1, in_flight)));
  // The progress callback counts the finished views 1, 2, ..., count, one call at a time.
  ASSERT_EQ(finished.size(), count);
  for (size_t n = 0; n < count; ++n) EXPECT_EQ(finished[n], n + 1);
}

TEST(ViewBatchesTest, EveryViewOnceAndAtMostInFlightAtOnce) {
  CheckBatches(0, 2);
  CheckBatches(1, 2);
  CheckBatches(7, 1);
  CheckBatches(7, 2);
  CheckBatches(9, 3);
  CheckBatches(5, 0);  // 0 means one at a time
}

TEST(ViewBatchesTest, AViewsExceptionReachesTheCaller) {
  EXPECT_THROW(ForEachViewInBatches(6, 2,
                                    [](size_t i) {
                                      if (i == 3) throw std::runtime_error("view 3 unreadable");
                                    }),
               std::runtime_error);
}

}  // namespace
}  // namespace sacfuse
