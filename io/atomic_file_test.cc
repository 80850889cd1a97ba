// Temporary file names carry their writer (host, pid), so a cleanup removes only files whose writer is provably
// gone: this host's pids that are not alive. Names of the older form "<path>.tmp-<pid>-<n>" and other hosts' are
// left to the callers' wider rules (jobs/output_lock.h).
#include "io/atomic_file.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "io/process_identity.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::TempDir;

TEST(AtomicFileTest, TemporaryNamesNameHostAndPid) {
  const std::string name = fs::path(TemporaryPathFor("/x/fused.laz")).filename().string();
  const auto owner = TemporaryFileOwnerOf(name);
  ASSERT_TRUE(owner) << name;
  EXPECT_EQ(owner->pid, ::getpid());
  EXPECT_FALSE(owner->host.empty());
  EXPECT_EQ(name.rfind("fused.laz.tmp-", 0), 0u) << name;
  EXPECT_NE(TemporaryPathFor("/x/a"), TemporaryPathFor("/x/a"));  // unique per call

  const auto older = TemporaryFileOwnerOf("3_4.laz.tmp-123-0");  // versions before the host was named
  ASSERT_TRUE(older);
  EXPECT_EQ(older->host, "");
  EXPECT_EQ(older->pid, 123);
  const auto dashed = TemporaryFileOwnerOf("a.json.tmp-node-7.cluster-4567-12");
  ASSERT_TRUE(dashed);
  EXPECT_EQ(dashed->host, "node-7.cluster");
  EXPECT_EQ(dashed->pid, 4567);
  for (const char* other : {"notes.tmp-draft", "a.tmp-", "a.tmp-12", "a.tmp-x-y", ".tmp-1-2", "a.tmp-h--3"}) {
    EXPECT_FALSE(IsTemporaryFileName(other)) << other;
  }
}

TEST(AtomicFileTest, CleanupRemovesOnlyFilesOfGoneProcessesOfThisHost) {
  TempDir dir;
  const std::string live = TemporaryPathFor((dir / "live.json").string());  // this process: alive
  const std::string host = TemporaryFileOwnerOf(fs::path(live).filename().string())->host;
  const std::string gone = (dir / ("gone.json.tmp-" + host + "-" + std::to_string(testing::GonePid()) + "-0")).string();
  const std::string elsewhere = (dir / "far.json.tmp-another-host-1-0").string();
  const std::string older = (dir / "old.json.tmp-999999-0").string();
  const std::string foreign = (dir / "notes.tmp-draft").string();
  for (const std::string& p : {live, gone, elsewhere, older, foreign}) std::ofstream(p) << "x";
  EXPECT_EQ(RemoveTemporaryFiles(dir.path().string()), std::vector<std::string>{gone});
  for (const std::string& p : {live, elsewhere, older, foreign}) EXPECT_TRUE(fs::exists(p)) << p;
  // A caller that knows no other process is there passes a wider rule; files of other names are never touched.
  std::vector<std::string> all = RemoveTemporaryFiles(dir.path().string(), false,
                                                      [](const TemporaryFileOwner&) { return true; });
  std::sort(all.begin(), all.end());
  std::vector<std::string> expected = {live, elsewhere, older};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(all, expected);
  EXPECT_TRUE(fs::exists(foreign));
}

TEST(AtomicFileTest, ReadSmallFileIsEmptyForMissingFiles) {
  TempDir dir;
  EXPECT_EQ(ReadSmallFile((dir / "none").string()), "");
  WriteFileAtomically((dir / "a" / "b.json").string(), "{}\n");
  EXPECT_EQ(ReadSmallFile((dir / "a" / "b.json").string()), "{}\n");
}

}  // namespace
}  // namespace sacfuse
