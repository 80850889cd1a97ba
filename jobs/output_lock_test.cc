// One output folder, one writer (jobs/output_lock.h): a second writer is refused naming the first (command, pid,
// host, start time); `tile` workers of another config or other inputs are refused while a writer holds the folder;
// the cleanup removes temporary files only when their writer is provably gone; a run's cloud of the other
// output.format is removed, not left stale beside the new one.
#include "jobs/output_lock.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "config/output_layout.h"
#include "io/atomic_file.h"
#include "io/process_identity.h"
#include "tests/support/error_of.h"
#include "tests/support/log_capture.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::LogCapture;
using sacfuse::testing::TempDir;

JobConfig ConfigIn(const TempDir& dir) {
  JobConfig config;
  config.output.dir = (dir / "out").string();
  return config;
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(OutputLockTest, SecondWriterIsRefusedNamingTheFirst) {
  TempDir dir;
  const JobConfig config = ConfigIn(dir);
  EXPECT_FALSE(LiveOutputWriter(config));
  OutputWriterLock first(config, "run");
  ASSERT_TRUE(first.locked());
  const std::string err = testing::ErrorOf<Error>([&] { OutputWriterLock second(config, "merge"); });
  EXPECT_TRUE(Has(err, config.output.dir + ": `sacfuse run` (pid " + std::to_string(::getpid()) + " on host " +
                           ThisHostName() + ", started "))
      << err;
  EXPECT_TRUE(Has(err, "is writing this output folder; one output folder has one writer")) << err;
  EXPECT_TRUE(Has(err, "`sacfuse merge --wait` waits")) << err;
  const auto writer = LiveOutputWriter(config);
  ASSERT_TRUE(writer);
  EXPECT_EQ(writer->command, "run");
  EXPECT_EQ(writer->pid, ::getpid());
  EXPECT_EQ(writer->config_hash, "");
  first.Record("hash-a", "digest-a");
  EXPECT_EQ(LiveOutputWriter(config)->config_hash, "hash-a");
  EXPECT_EQ(LiveOutputWriter(config)->inputs_digest, "digest-a");
}

TEST(OutputLockTest, LockIsReleasedWhenTheWriterIsKilled) {
  TempDir dir;
  const JobConfig config = ConfigIn(dir);
  const std::string ready = (dir / "ready").string();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    OutputWriterLock held(config, "run");
    std::ofstream(ready) << "locked";
    for (;;) ::pause();
  }
  for (int i = 0; i < 500 && !fs::exists(ready); ++i) ::usleep(10000);
  ASSERT_TRUE(LiveOutputWriter(config));
  EXPECT_EQ(LiveOutputWriter(config)->pid, child);
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_FALSE(LiveOutputWriter(config));
  EXPECT_NO_THROW(OutputWriterLock(config, "run"));
}

TEST(OutputLockTest, WorkerOfAnotherJobIsRefusedWhileAWriterHoldsTheFolder) {
  TempDir dir;
  const JobConfig config = ConfigIn(dir);
  EXPECT_NO_THROW(CheckWorkerMatchesWriter(config, "hash-b", "digest-b"));  // no writer
  OutputWriterLock writer(config, "run");
  EXPECT_NO_THROW(CheckWorkerMatchesWriter(config, "hash-b", "digest-b"));  // hash not recorded yet
  writer.Record("hash-a", "digest-a");
  EXPECT_NO_THROW(CheckWorkerMatchesWriter(config, "hash-a", "digest-a"));
  const std::string settings = testing::ErrorOf<Error>([&] { CheckWorkerMatchesWriter(config, "hash-b", "digest-a"); });
  EXPECT_TRUE(Has(settings, "with other result-affecting settings (config hash hash-a, this worker's hash-b)"))
      << settings;
  EXPECT_TRUE(Has(settings, "its merge would not take this worker's tiles")) << settings;
  const std::string inputs = testing::ErrorOf<Error>([&] { CheckWorkerMatchesWriter(config, "hash-a", "digest-b"); });
  EXPECT_TRUE(Has(inputs, "with other inputs (inputs digest digest-a, this worker's digest-b")) << inputs;
}

TEST(OutputLockTest, CleanupRemovesOnlyFilesWhoseWriterIsProvablyGone) {
  TempDir dir;
  const JobConfig config = ConfigIn(dir);
  fs::create_directories(TilesDir(config));
  const std::string live = TemporaryPathFor(FusedLasPath(config));  // this process: alive
  const std::string host = TemporaryFileOwnerOf(fs::path(live).filename().string())->host;
  const std::string gone = TilesDir(config) + "/3_4.laz.tmp-" + host + "-" + std::to_string(testing::GonePid()) + "-0";
  const std::string far = TilesDir(config) + "/3_5.laz.tmp-another-host-77-0";
  const std::string older = config.output.dir + "/run_report.json.tmp-999999-3";
  for (const std::string& p : {live, gone, far, older}) std::ofstream(p) << "half-written";
  LogCapture log;
  {
    // A worker (no writer lock) removes only this host's files of gone pids.
    EXPECT_EQ(RemoveTemporaryFilesOfGoneProcesses(config, nullptr), 1u);
    EXPECT_FALSE(fs::exists(gone));
    EXPECT_TRUE(fs::exists(live) && fs::exists(far) && fs::exists(older));
  }
  {
    // A writer while a worker holds the shared lock: still only what it can prove.
    OutputWriterLock writer(config, "run");
    const OutputWorkerLock worker(config);
    EXPECT_EQ(RemoveTemporaryFilesOfGoneProcesses(config, &writer), 0u);
    EXPECT_TRUE(fs::exists(far) && fs::exists(older));
  }
  {
    // A writer alone in the folder also removes what it cannot attribute (other hosts, older versions), but never
    // a file named with a live pid of this host.
    OutputWriterLock writer(config, "run");
    EXPECT_EQ(RemoveTemporaryFilesOfGoneProcesses(config, &writer), 2u);
    EXPECT_FALSE(fs::exists(far) || fs::exists(older));
    EXPECT_TRUE(fs::exists(live));
  }
  EXPECT_TRUE(Has(log.text(), "removed " + gone + " (left by a process that is gone)")) << log.text();
}

TEST(OutputLockTest, CloudOfTheOtherFormatIsRemovedNotLeftStale) {
  TempDir dir;
  JobConfig config = ConfigIn(dir);
  config.output.format = "las";
  fs::create_directories(config.output.dir);
  std::ofstream(FusedPathOfFormat(config, "laz")) << "an earlier run's cloud";
  std::ofstream(FusedLasPath(config)) << "this run's cloud";
  LogCapture log;
  RemoveOtherFormatCloud(config);
  EXPECT_FALSE(fs::exists(FusedPathOfFormat(config, "laz")));
  EXPECT_TRUE(fs::exists(FusedLasPath(config)));
  EXPECT_TRUE(Has(log.text(), "the cloud of an earlier run with output.format laz")) << log.text();
}

}  // namespace
}  // namespace sacfuse
