#include "jobs/view_batches.h"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

namespace sacfuse {
namespace {

// Every index once, never more than `in_flight` at once.
void CheckBatches(size_t count, size_t in_flight) {
  std::vector<std::atomic<int>> calls(count);
  std::atomic<int> running{0}, most{0};
  std::vector<size_t> finished;
  ForEachViewInFlight(count, in_flight, [&](size_t i) {
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

// No batches: while the first view is still being prepared, the others go on one after another in the other slot
// (in batches of two, view 2 would wait for view 0).
TEST(ViewBatchesTest, ASlowViewHoldsUpNoOtherView) {
  if (tbb::this_task_arena::max_concurrency() < 2) GTEST_SKIP() << "needs two threads";
  std::atomic<int> others_done{0};
  bool others_finished_meanwhile = false;
  ForEachViewInFlight(6, 2, [&](size_t i) {
    if (i != 0) {
      ++others_done;
      return;
    }
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (others_done < 5 && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    others_finished_meanwhile = others_done == 5;
  });
  EXPECT_TRUE(others_finished_meanwhile);
}

TEST(ViewBatchesTest, AViewsExceptionReachesTheCaller) {
  EXPECT_THROW(ForEachViewInFlight(6, 2,
                                    [](size_t i) {
                                      if (i == 3) throw std::runtime_error("view 3 unreadable");
                                    }),
               std::runtime_error);
}

}  // namespace
}  // namespace sacfuse
