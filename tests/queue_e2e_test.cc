// End-to-end: the tile list as a work queue (simulate --preset tiny --seed 3, 20 m tiles, 5 m halo).
// (a) `plan --list | parallel -j 3 sacfuse tile --id {}` then `merge` gives the fused.laz of a plain `run` (bytes
// equal except the header's creation date); (b) no tile is computed twice and no claim file is left; (c) the same
// `tile --id` twice at once computes it once; (d) `merge` before the tiles are done exits 1 naming a missing
// tile; (e) `run` and `tile` workers mixed on one DIR compute every tile once and give the same cloud.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::CountFilesNamedWith;
using testing::ReadFileBytes;
using testing::WithoutLasCreationDate;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;
using testing::TempDir;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

// How often each tile id follows "computing tile " in `log`.
std::map<std::string, int> ComputedTiles(const std::string& log) {
  std::map<std::string, int> n;
  const std::string key = "computing tile ";
  for (size_t p = log.find(key); p != std::string::npos; p = log.find(key, p + 1)) {
    const size_t b = p + key.size();
    ++n[log.substr(b, log.find_first_of(" \n", b) - b)];
  }
  return n;
}

bool HaveParallel() { return std::system("parallel --version >/dev/null 2>&1") == 0; }

class QueueEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock();
    std::string out;
    for (const std::string name : {"ref", "par", "dup", "early", "mixed"}) {
      std::ofstream(Config(name)) << "input: {path: " << Block().string() << "}\n"
                                  << "output: {dir: " << Out(name).string() << "}\n"
                                  << "tiling: {tile_size_m: 20, halo_m: 5}\n";
    }
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("ref")), &out), 0) << out;
    reference_ = WithoutLasCreationDate(ReadFileBytes(Out("ref") / "fused.laz"));
    ASSERT_EQ(RunCommand(SacfuseBinary() + " plan --list " + ShellQuote(Config("early")) + " 2>/dev/null", &out), 0);
    ids_ = Lines(out);
  }
  static std::string Tile(const std::string& name) {
    return SacfuseBinary() + " tile " + ShellQuote(Config(name)) + " --id ";
  }
  static void ExpectEveryTileOnceAndReferenceCloud(const std::string& name, const std::string& log) {
    const std::map<std::string, int> computed = ComputedTiles(log);
    EXPECT_EQ(computed.size(), ids_.size()) << log;
    for (const auto& id : ids_) EXPECT_EQ(computed.count(id) ? computed.at(id) : 0, 1) << "tile " << id;
    EXPECT_EQ(CountFilesNamedWith(Out(name) / "tiles", ".done.json"), ids_.size());
    EXPECT_EQ(CountFilesNamedWith(Out(name) / "tiles", ".claim"), 0u);
    EXPECT_EQ(CountFilesNamedWith(Out(name), ".tmp-"), 0u);
    EXPECT_TRUE(WithoutLasCreationDate(ReadFileBytes(Out(name) / "fused.laz")) == reference_)
        << "fused.laz differs from the plain run's";
  }
  static inline std::string reference_;
  static inline std::vector<std::string> ids_;
};

TEST_F(QueueEndToEndTest, PlanListPrintsOnlyTilesWithViews) {
  ASSERT_EQ(ids_.size(), 65u);  // the tiny block's tiles with views (docs/large-blocks.md)
  for (const auto& id : ids_) EXPECT_NE(id.find('_'), std::string::npos) << id;
}

TEST_F(QueueEndToEndTest, ParallelTileWorkersThenMergeEqualPlainRun) {
  if (!HaveParallel()) GTEST_SKIP() << "GNU parallel is not installed (tools/install_deps.sh installs it)";
  std::string log;
  const std::string cmd = SacfuseBinary() + " plan --list " + ShellQuote(Config("par")) + " 2>/dev/null | parallel -j 3 " +
                          Tile("par") + "{}";
  ASSERT_EQ(RunCommand(cmd, &log), 0) << log;
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " merge " + ShellQuote(Config("par")), &out), 0) << out;
  ExpectEveryTileOnceAndReferenceCloud("par", log);
}

TEST_F(QueueEndToEndTest, SameTileTwiceAtOnceIsComputedOnce) {
  const std::string id = ids_.at(ids_.size() / 2);
  std::string log;
  const std::string one = "(" + Tile("dup") + id + "; echo exit=$?)";
  ASSERT_EQ(RunCommand("(" + one + " & " + one + " & wait)", &log), 0) << log;
  EXPECT_EQ(ComputedTiles(log)[id], 1) << log;
  EXPECT_EQ(ComputedTiles(log).size(), 1u) << log;
  size_t ok = 0;
  for (size_t p = log.find("exit=0"); p != std::string::npos; p = log.find("exit=0", p + 1)) ++ok;
  EXPECT_EQ(ok, 2u) << log;
  EXPECT_TRUE(fs::exists(Out("dup") / "tiles" / (id + ".done.json")));
  EXPECT_EQ(CountFilesNamedWith(Out("dup") / "tiles", ".claim"), 0u);
  // A third call finds it done.
  ASSERT_EQ(RunCommand(Tile("dup") + id, &log), 0) << log;
  EXPECT_NE(log.find("tile " + id + ": done, skipped"), std::string::npos) << log;
}

TEST_F(QueueEndToEndTest, MergeBeforeAllTilesAreDoneExits1NamingMissingTile) {
  std::string out;
  ASSERT_EQ(RunCommand(Tile("early") + ids_.front(), &out), 0) << out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " merge " + ShellQuote(Config("early")), &out), 1) << out;
  EXPECT_NE(out.find("Missing:"), std::string::npos) << out;
  EXPECT_NE(out.find(" " + ids_.back()), std::string::npos) << out;
  EXPECT_EQ(out.find(" " + ids_.front() + " "), std::string::npos) << out;  // that one is done
  EXPECT_FALSE(fs::exists(Out("early") / "fused.laz"));
}

TEST_F(QueueEndToEndTest, RunAndTileWorkersMixed) {
  if (!HaveParallel()) GTEST_SKIP() << "GNU parallel is not installed (tools/install_deps.sh installs it)";
  std::string log;
  const std::string workers = "(" + SacfuseBinary() + " plan --list " + ShellQuote(Config("mixed")) +
                              " 2>/dev/null | tac | parallel -j 1 " + Tile("mixed") + "{})";
  const std::string run = "(" + SacfuseBinary() + " run " + ShellQuote(Config("mixed")) + "; echo run_exit=$?)";
  ASSERT_EQ(RunCommand("(" + workers + " & " + run + " & wait)", &log), 0) << log;
  EXPECT_NE(log.find("run_exit=0"), std::string::npos) << log;
  ExpectEveryTileOnceAndReferenceCloud("mixed", log);
}

}  // namespace
}  // namespace sacfuse
