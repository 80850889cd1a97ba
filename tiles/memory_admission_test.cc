#include "tiles/memory_admission.h"

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

TEST(MemoryAdmissionTest, ConcurrentReservationsNeverExceedThePool) {
  MemoryAdmission admission(100);
  std::atomic<int64_t> in_use{0}, worst{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 6; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 50; ++i) {
        const uint64_t bytes = 20 + 10 * ((t + i) % 5);  // 20..60
        MemoryReservation hold(admission, bytes);
        const int64_t now = in_use += static_cast<int64_t>(bytes);
        int64_t seen = worst.load();
        while (now > seen && !worst.compare_exchange_weak(seen, now)) {
        }
        std::this_thread::sleep_for(std::chrono::microseconds(50));
        in_use -= static_cast<int64_t>(bytes);
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_LE(worst.load(), 100);
  EXPECT_GT(worst.load(), 60);  // reservations did overlap
  EXPECT_LE(admission.peak_reserved(), 100u);
}

TEST(MemoryAdmissionTest, ARequestLargerThanThePoolRunsAlone) {
  MemoryAdmission admission(10);
  admission.Acquire(50);  // nothing else reserved: admitted
  std::atomic<bool> second{false};
  std::thread t([&] {
    admission.Acquire(5);
    second = true;
    admission.Release(5);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(second.load());  // waits for the big one
  admission.Release(50);
  t.join();
  EXPECT_TRUE(second.load());
}

}  // namespace
}  // namespace sacfuse
