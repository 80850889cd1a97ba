#include "io/stage_clock.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

// Spins for about `seconds` of CPU time of this thread.
double Spin(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  double x = 0.0;
  while (std::chrono::steady_clock::now() < end) x = std::sqrt(x + 1.0);
  return x;
}

TEST(StageClockTest, StagesInOrderWithTheirWallAndCpuTime) {
  StageClock clock;
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  const StageTime& sleeping = clock.Mark("sleeping");
  EXPECT_EQ(sleeping.name, "sleeping");
  EXPECT_GE(sleeping.wall_s, 0.029);
  EXPECT_LT(sleeping.cpu_s, sleeping.wall_s);  // asleep: little CPU
  EXPECT_GT(Spin(0.05), 0.0);
  clock.Mark("spinning");
  ASSERT_EQ(clock.stages().size(), 2u);
  EXPECT_EQ(clock.stages()[0].name, "sleeping");
  EXPECT_EQ(clock.stages()[1].name, "spinning");
  EXPECT_GT(clock.stages()[1].cpu_s, 0.0);
  EXPECT_GT(clock.stages()[1].peak_rss_mib, 0.0);
  EXPECT_GE(clock.TotalWallSeconds(), clock.stages()[0].wall_s + clock.stages()[1].wall_s);
}

TEST(StageClockTest, SkipLeavesTimeOutOfEveryStage) {
  StageClock clock;
  std::this_thread::sleep_for(std::chrono::milliseconds(40));
  clock.Skip();
  const StageTime& t = clock.Mark("after the skip");
  EXPECT_LT(t.wall_s, 0.035);
  EXPECT_GE(clock.TotalWallSeconds(), 0.04);
}

TEST(StageClockTest, TableHasOneRowPerStageAndATotal) {
  const std::string table = FormatStageTable({{"open input", 0.5, 0.25, 100, 90}, {"fusion", 2.0, 3.9, 400, 300}},
                                             2.5, 4.15);
  EXPECT_NE(table.find("stage"), std::string::npos);
  EXPECT_NE(table.find("open input"), std::string::npos);
  EXPECT_NE(table.find("1.95"), std::string::npos);  // fusion's CPU / wall
  EXPECT_NE(table.find("total"), std::string::npos);
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 4);
}

}  // namespace
}  // namespace sacfuse
