// The advisory lock of io/file_lock.h: exclusive against exclusive and shared, shared beside shared, released when
// the holder closes it or its process dies (kill -9), a brief probe not taken for a holder, and the holder's
// description readable by those who find it locked.
#include "io/file_lock.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using Mode = FileLock::Mode;
using Outcome = FileLock::Outcome;
using sacfuse::testing::TempDir;

TEST(FileLockTest, ExclusiveExcludesEveryOtherLockAndSharedAdmitsShared) {
  TempDir dir;
  const std::string path = (dir / "x.lock").string();
  {
    FileLock a(path, Mode::kExclusive);
    ASSERT_TRUE(a.locked());
    EXPECT_EQ(FileLock(path, Mode::kExclusive).outcome(), Outcome::kBusy);
    EXPECT_EQ(FileLock(path, Mode::kShared).outcome(), Outcome::kBusy);
    EXPECT_FALSE(LockIsFree(path, Mode::kShared));
  }
  EXPECT_TRUE(LockIsFree(path, Mode::kExclusive));  // released with the object
  FileLock s1(path, Mode::kShared), s2(path, Mode::kShared);
  EXPECT_TRUE(s1.locked() && s2.locked());
  EXPECT_EQ(FileLock(path, Mode::kExclusive).outcome(), Outcome::kBusy);
  EXPECT_TRUE(LockIsFree(path, Mode::kShared));
  s1.Release();
  s2.Release();
  EXPECT_TRUE(FileLock(path, Mode::kExclusive).locked());
  EXPECT_TRUE(LockIsFree((dir / "never-created.lock").string(), Mode::kExclusive));
}

TEST(FileLockTest, HolderWritesItsDescriptionForOthersToRead) {
  TempDir dir;
  const std::string path = (dir / "x.lock").string();
  FileLock a(path, Mode::kExclusive);
  a.WriteContents("a rather long first description\n");
  a.WriteContents("short\n");  // replaces, not overwrites in place
  EXPECT_EQ(ReadSmallFile(path), "short\n");
}

TEST(FileLockTest, ReleasedWhenTheHolderIsKilled) {
  TempDir dir;
  const std::string path = (dir / "x.lock").string();
  const std::string ready = (dir / "ready").string();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    FileLock held(path, Mode::kExclusive);
    std::ofstream(ready) << "locked";
    for (;;) ::pause();  // until killed
  }
  for (int i = 0; i < 500 && !std::filesystem::exists(ready); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(FileLock(path, Mode::kExclusive).outcome(), Outcome::kBusy);
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(FileLock(path, Mode::kExclusive).locked());
}

TEST(FileLockTest, PatienceOutlastsABriefProbeAndWaitBlocksUntilFree) {
  TempDir dir;
  const std::string path = (dir / "x.lock").string();
  auto holder = std::make_unique<FileLock>(path, Mode::kShared);
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    holder.reset();
  });
  const auto start = std::chrono::steady_clock::now();
  FileLock patient(path, Mode::kExclusive, /*patience_s=*/5.0);
  release.join();
  EXPECT_TRUE(patient.locked());
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(4));
  patient.Release();
  auto second = std::make_unique<FileLock>(path, Mode::kExclusive);
  std::thread release2([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    second.reset();
  });
  FileLock waiting(path, Mode::kExclusive, 0.0, /*wait=*/true);
  release2.join();
  EXPECT_TRUE(waiting.locked());
}

}  // namespace
}  // namespace sacfuse
