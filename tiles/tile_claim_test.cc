#include "tiles/tile_claim.h"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

constexpr double kHour = 3600.0;

// Writes a claim file as another worker would have.
void WriteClaim(const std::string& dir, const std::string& id, const std::string& host, int64_t pid,
                int64_t start_unix_s) {
  std::ofstream(TileClaimPath(dir, id)) << nlohmann::json{{"host", host},
                                                          {"pid", pid},
                                                          {"start_unix_s", start_unix_s},
                                                          {"token", "other"}}.dump();
}

int64_t Now() { return static_cast<int64_t>(::time(nullptr)); }

TEST(TileClaimTest, ExclusiveCreateRefusesSecondClaimerAndReleases) {
  TempDir dir;
  const std::string d = dir.path().string();
  const ClaimAttempt first = TryClaimTile(d, "3_4", kHour);
  ASSERT_TRUE(first.claimed);
  EXPECT_FALSE(first.took_over);
  ASSERT_TRUE(fs::exists(TileClaimPath(d, "3_4")));
  const auto info = ReadTileClaim(d, "3_4");
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->pid, ::getpid());
  EXPECT_EQ(info->host, ThisHostName());
  EXPECT_TRUE(TileClaimIsLive(d, "3_4", kHour));
  EXPECT_TRUE(AnyLiveTileClaim(d, kHour));

  const ClaimAttempt second = TryClaimTile(d, "3_4", kHour);  // our own pid is alive: live claim
  EXPECT_FALSE(second.claimed);
  EXPECT_NE(second.holder.find("pid " + std::to_string(::getpid())), std::string::npos) << second.holder;
  EXPECT_TRUE(TryClaimTile(d, "3_5", kHour).claimed);  // other tiles are independent

  ReleaseTileClaim(d, "3_4", "not-my-token");  // never removes another worker's claim
  EXPECT_TRUE(fs::exists(TileClaimPath(d, "3_4")));
  ReleaseTileClaim(d, "3_4", first.token);
  EXPECT_FALSE(fs::exists(TileClaimPath(d, "3_4")));
  EXPECT_TRUE(TryClaimTile(d, "3_4", kHour).claimed);
}

TEST(TileClaimTest, GuardRemovesClaimWhenDone) {
  TempDir dir;
  const std::string d = dir.path().string();
  {
    const ClaimAttempt a = TryClaimTile(d, "1_1", kHour);
    ASSERT_TRUE(a.claimed);
    TileClaimGuard guard(d, "1_1", a.token);
    EXPECT_TRUE(fs::exists(TileClaimPath(d, "1_1")));
  }
  EXPECT_FALSE(fs::exists(TileClaimPath(d, "1_1")));
  EXPECT_FALSE(AnyLiveTileClaim(d, kHour));
}

TEST(TileClaimTest, DeadPidClaimIsTakenOver) {
  TempDir dir;
  const std::string d = dir.path().string();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);  // reaped: the pid no longer exists
  WriteClaim(d, "2_2", ThisHostName(), child, Now());
  EXPECT_FALSE(TileClaimIsLive(d, "2_2", kHour));
  const ClaimAttempt a = TryClaimTile(d, "2_2", kHour);
  ASSERT_TRUE(a.claimed);
  EXPECT_TRUE(a.took_over);
  EXPECT_EQ(ReadTileClaim(d, "2_2")->pid, ::getpid());
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(d)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1u);  // the stale claim was removed, not left under its moved name
}

TEST(TileClaimTest, RemoveStaleClaimsKeepsLiveOnes) {
  TempDir dir;
  const std::string d = dir.path().string();
  WriteClaim(d, "5_5", "some-other-host", 1, Now() - 2 * static_cast<int64_t>(kHour));  // timed out
  const ClaimAttempt live = TryClaimTile(d, "6_6", kHour);
  ASSERT_TRUE(live.claimed);
  EXPECT_EQ(RemoveStaleTileClaims(d, kHour), 1u);
  EXPECT_FALSE(fs::exists(TileClaimPath(d, "5_5")));
  EXPECT_EQ(ReadTileClaim(d, "6_6")->token, live.token);
}

TEST(TileClaimTest, OldClaimOfAnotherHostIsTakenOverOnlyAfterTimeout) {
  TempDir dir;
  const std::string d = dir.path().string();
  WriteClaim(d, "0_0", "some-other-host", 1, Now() - 100);  // pid of another host: cannot be checked
  const ClaimAttempt young = TryClaimTile(d, "0_0", kHour);
  EXPECT_FALSE(young.claimed);
  EXPECT_NE(young.holder.find("some-other-host pid 1"), std::string::npos) << young.holder;
  const ClaimAttempt old = TryClaimTile(d, "0_0", /*timeout_s=*/50);
  EXPECT_TRUE(old.claimed);
  EXPECT_TRUE(old.took_over);
}

TEST(TileClaimTest, UnreadableClaimIsLiveForOneMinuteThenTakenOver) {
  TempDir dir;
  const std::string d = dir.path().string();
  const std::string path = TileClaimPath(d, "4_4");
  std::ofstream(path) << "";  // what a worker killed between create and write left before claims were linked
  EXPECT_TRUE(TileClaimIsLive(d, "4_4", kHour));
  EXPECT_FALSE(TryClaimTile(d, "4_4", kHour).claimed);
  fs::last_write_time(path, fs::last_write_time(path) - std::chrono::seconds(120));
  EXPECT_FALSE(TileClaimIsLive(d, "4_4", kHour));  // not 6 h: a resumed run does not wait on it
  const ClaimAttempt attempt = TryClaimTile(d, "4_4", kHour);
  EXPECT_TRUE(attempt.claimed);
  EXPECT_TRUE(attempt.took_over);
  EXPECT_EQ(ReadTileClaim(d, "4_4")->token, attempt.token);
}

TEST(TileClaimTest, ClaimAppearsWholeAndLeavesNoTemporaryFile) {
  TempDir dir;
  const std::string d = dir.path().string();
  for (int i = 0; i < 20; ++i) {
    const std::string id = "0_" + std::to_string(i);
    const ClaimAttempt attempt = TryClaimTile(d, id, kHour);
    ASSERT_TRUE(attempt.claimed);
    const auto claim = ReadTileClaim(d, id);
    ASSERT_TRUE(claim.has_value());
    EXPECT_EQ(claim->pid, static_cast<int64_t>(::getpid()));
    EXPECT_EQ(claim->token, attempt.token);
  }
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    EXPECT_EQ(e.path().extension(), ".claim") << e.path();
    ++files;
  }
  EXPECT_EQ(files, 20u);
}

}  // namespace
}  // namespace sacfuse
