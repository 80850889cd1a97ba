#include "tools/bench/child_process.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using testing::ReadFileBytes;
using testing::TempDir;

TEST(ChildProcessTest, ReportsTheExitCode) {
  const ChildResult r = RunChildProcess({"/bin/sh", "-c", "exit 3"}, "");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.term_signal, 0);
  EXPECT_GE(r.wall_s, 0.0);
  EXPECT_LT(r.wall_s, 10.0);
  EXPECT_EQ(RunChildProcess({"true"}, "").exit_code, 0);  // looked up on PATH
}

TEST(ChildProcessTest, ReportsAKillingSignal) {
  const ChildResult r = RunChildProcess({"/bin/sh", "-c", "kill -9 $$"}, "");
  EXPECT_EQ(r.term_signal, 9);
  EXPECT_EQ(r.exit_code, 128 + 9);
}

TEST(ChildProcessTest, PeakRssOfAnAllocatingChildIsPlausible) {
  // dd's 64 MiB block buffer is filled from /dev/zero, so it is resident.
  const ChildResult big = RunChildProcess({"dd", "if=/dev/zero", "of=/dev/null", "bs=64M", "count=1"}, "");
  ASSERT_EQ(big.exit_code, 0);
  EXPECT_GT(big.peak_rss_mib, 60.0);
  EXPECT_LT(big.peak_rss_mib, 200.0);
  const ChildResult small = RunChildProcess({"/bin/sh", "-c", "exit 0"}, "");
  EXPECT_GT(small.peak_rss_mib, 0.0);
  EXPECT_LT(small.peak_rss_mib, small.parent_rss_at_fork_mib + 30.0);
  EXPECT_GT(small.parent_rss_at_fork_mib, 0.0);
}

// Linux counts the anonymous pages a child inherits at fork into its ru_maxrss; parent_rss_at_fork_mib says how
// much that was, so a reader can tell when the figure is the parent's rather than the child's.
TEST(ChildProcessTest, ReportsWhatTheChildInheritedAtFork) {
  std::vector<char> held(96 << 20);
  std::memset(held.data(), 1, held.size());
  const ChildResult r = RunChildProcess({"/bin/true"}, "");
  EXPECT_GT(r.parent_rss_at_fork_mib, 90.0);
  EXPECT_GT(r.peak_rss_mib, 0.5 * r.parent_rss_at_fork_mib);  // the inherited pages show in the child's figure
  EXPECT_EQ(held[12345], 1);
}

TEST(ChildProcessTest, StreamsStdoutAndStderrIntoTheLog) {
  TempDir dir;
  const std::string log = (dir / "sub" / "child.log").string();
  ASSERT_EQ(RunChildProcess({"/bin/sh", "-c", "echo out; echo err >&2"}, log).exit_code, 0);
  ASSERT_EQ(RunChildProcess({"/bin/sh", "-c", "echo again"}, log).exit_code, 0);  // appends
  EXPECT_EQ(ReadFileBytes(log), "out\nerr\nagain\n");
}

TEST(ChildProcessTest, MissingProgramThrowsNamingIt) {
  try {
    RunChildProcess({"/no/such/program", "x"}, "");
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/program"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RunChildProcess({"sacfuse-no-such-program-on-path"}, ""), Error);
  EXPECT_EQ(FindExecutable("sacfuse-no-such-program-on-path"), "");
  EXPECT_EQ(FindExecutable("sh").empty(), false);
  // A file that exists but cannot be executed (not executable / exec fails).
  TempDir dir;
  const std::string script = (dir / "not_exec.sh").string();
  { std::ofstream(script) << "#!/bin/sh\nexit 0\n"; }
  EXPECT_THROW(RunChildProcess({script}, ""), Error);
  // Executable but not a program the kernel can start: the exec error comes back from the child.
  const std::string garbage = (dir / "garbage").string();
  { std::ofstream(garbage) << "\x01\x02 not a program\n"; }
  std::filesystem::permissions(garbage, std::filesystem::perms::owner_all);
  try {
    RunChildProcess({garbage}, "");
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot execute"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sacfuse
