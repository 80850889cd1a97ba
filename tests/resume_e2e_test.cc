// End-to-end: per-tile outputs and resume of a tiled run (simulate --preset tiny, 20 m tiles, 5 m halo).
// (a) an uninterrupted run; (b) three kill -9 at random moments, then a run to completion, gives the same
// fused.laz (bytes equal except the header's creation date) and the same dsm.tif and ortho.tif (every byte; the
// runs have a CRS, so they write the DSM and the true orthophoto) and leaves no "*.tmp-*" file; (c) --tiles reruns
// only the named tile; (d) status lists every tile done, and a tile whose LAS was deleted as pending; (e) a
// truncated tile LAS is recomputed by the next run; (f) a failing tile is recorded and the others go on.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::CountFilesNamedWith;
using testing::ReadFileBytes;
using testing::WithoutLasCreationDate;
using testing::RunCommand;
using testing::ShellQuote;
using testing::SacfuseBinary;
using testing::TempDir;

// done.json contents by tile id.
std::map<std::string, std::string> DoneMarkers(const fs::path& tiles_dir) {
  std::map<std::string, std::string> markers;
  for (const auto& e : fs::directory_iterator(tiles_dir)) {
    const std::string name = e.path().filename().string();
    const auto pos = name.find(".done.json");
    if (pos != std::string::npos) markers[name.substr(0, pos)] = ReadFileBytes(e.path());
  }
  return markers;
}

size_t TemporaryFilesUnder(const fs::path& dir) { return CountFilesNamedWith(dir, ".tmp-"); }

// The "tiles: N computed, M done and skipped" line of a run's output.
std::string TilesLine(const std::string& out) {
  const auto begin = out.find("\ntiles: ");
  if (begin == std::string::npos) return "";
  return out.substr(begin + 1, out.find('\n', begin + 1) - begin - 1);
}

class ResumeEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock();
    std::string out;
    for (const std::string name : {"a", "b"}) {
      // With a CRS the run writes its DSM too (output.dsm: auto), resumed like the cloud.
      std::ofstream(Config(name)) << "crs: \"EPSG:25832\"\n"
                                  << "input: {path: " << Block().string() << "}\n"
                                  << "output: {dir: " << Out(name).string() << "}\n"
                                  << "tiling: {tile_size_m: 20, halo_m: 5}\n";
    }
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("a")), &out), 0) << out;
    run_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    reference_ = WithoutLasCreationDate(ReadFileBytes(Out("a") / "fused.laz"));
    reference_dsm_ = ReadFileBytes(Out("a") / "dsm.tif");
    reference_ortho_ = ReadFileBytes(Out("a") / "ortho.tif");
  }
  static fs::path Tiles(const std::string& name) { return Out(name) / "tiles"; }
  // A run that waits on a tile claim forever fails here after 5 minutes with its output (exit 124), not at
  // ctest's timeout with none.
  static std::string Run(const std::string& name, const std::string& extra, int* code) {
    std::string out;
    *code = RunCommand("timeout -k 10 300 " + SacfuseBinary() + " run " + ShellQuote(Config(name)) + extra, &out);
    return out;
  }
  static void ExpectFusedMatchesReference(const std::string& name) {
    const std::string fused = WithoutLasCreationDate(ReadFileBytes(Out(name) / "fused.laz"));
    EXPECT_GT(reference_.size(), 100000u);
    EXPECT_EQ(fused.size(), reference_.size());
    EXPECT_TRUE(fused == reference_) << name << "/fused.laz differs from the uninterrupted run's";
    const std::string dsm = ReadFileBytes(Out(name) / "dsm.tif");
    EXPECT_GT(reference_dsm_.size(), 1000u);
    EXPECT_TRUE(dsm == reference_dsm_) << name << "/dsm.tif differs from the uninterrupted run's";
    const std::string ortho = ReadFileBytes(Out(name) / "ortho.tif");
    EXPECT_GT(reference_ortho_.size(), 1000u);
    EXPECT_TRUE(ortho == reference_ortho_) << name << "/ortho.tif differs from the uninterrupted run's";
  }

  static inline std::string reference_;
  static inline std::string reference_dsm_;
  static inline std::string reference_ortho_;
  static inline double run_seconds_ = 0.0;
};

TEST_F(ResumeEndToEndTest, UninterruptedRunWritesTileFilesAndStatusListsAllDone) {
  const nlohmann::json manifest = nlohmann::json::parse(ReadFileBytes(Tiles("a") / "manifest.json"));
  const size_t tiles = manifest.at("tiles").size();
  ASSERT_GT(tiles, 4u);
  EXPECT_EQ(DoneMarkers(Tiles("a")).size(), tiles);
  EXPECT_TRUE(fs::exists(Tiles("a") / "run_config.yaml"));
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config("a")), &out), 0) << out;
  EXPECT_NE(out.find(std::to_string(tiles) + " tiles with views: " + std::to_string(tiles) + " done"),
            std::string::npos)
      << out;
  for (const auto& id : manifest.at("tiles")) {
    EXPECT_NE(out.find("done     " + id.get<std::string>() + "\n"), std::string::npos) << out;
  }
  // Everything done: a second run skips every tile and merges the same cloud.
  int code = 0;
  out = Run("a", "", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("0 computed, " + std::to_string(tiles) + " done and skipped"), std::string::npos) << out;
  EXPECT_NE(out.find(": done, skipped"), std::string::npos);
  ExpectFusedMatchesReference("a");
  std::printf("resume e2e: uninterrupted tiled run %.2f s, %zu tiles with views\n", run_seconds_, tiles);
}

TEST_F(ResumeEndToEndTest, ThreeKillsThenResumeGiveTheUninterruptedCloud) {
  std::random_device seed_source;
  const unsigned seed = seed_source();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> delay(0.3, 2.0);
  for (int kill = 0; kill < 3; ++kill) {
    const double s = delay(rng);
    char command[1024];
    std::snprintf(command, sizeof(command),
                  "%s run %s >/dev/null 2>&1 & pid=$!; sleep %.2f; kill -9 $pid 2>/dev/null; wait $pid",
                  SacfuseBinary().c_str(), ShellQuote(Config("b")).c_str(), s);
    // 137 = killed by SIGKILL; 0 = the run had already finished (the resumed part of a tiny run is short).
    const int status = RunCommand(command);
    const size_t done = fs::exists(Tiles("b")) ? DoneMarkers(Tiles("b")).size() : 0;
    std::printf("resume e2e: kill -9 #%d after %.2f s (seed %u): %s, %zu tiles done, %zu temporary files left\n",
                kill + 1, s, seed, status == 0 ? "run had finished" : "killed mid-run", done,
                fs::exists(Out("b")) ? TemporaryFilesUnder(Out("b")) : 0u);
  }
  int code = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string out = Run("b", "", &code);
  ASSERT_EQ(code, 0) << out;
  std::printf("resume e2e: resumed run %.2f s: %s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), TilesLine(out).c_str());
  ExpectFusedMatchesReference("b");
  EXPECT_EQ(TemporaryFilesUnder(Out("b")), 0u);
}

TEST_F(ResumeEndToEndTest, RerunOfOneTileRecomputesOnlyIt) {
  const auto before = DoneMarkers(Tiles("a"));
  const std::string id = nlohmann::json::parse(ReadFileBytes(Tiles("a") / "manifest.json")).at("tiles").at(3);
  int code = 0;
  std::string out = Run("a", " --tiles " + id, &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("1 computed"), std::string::npos) << out;
  const auto after = DoneMarkers(Tiles("a"));
  ASSERT_EQ(after.size(), before.size());
  for (const auto& [tile, marker] : before) {
    if (tile == id) {
      EXPECT_NE(after.at(tile), marker) << "tile " << tile << " was not recomputed";
    } else {
      EXPECT_EQ(after.at(tile), marker) << "tile " << tile << " was recomputed";
    }
  }
  ExpectFusedMatchesReference("a");
  out = Run("a", " --tiles " + id + ",99_99,x", &code);
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("99_99, x"), std::string::npos) << out;
}

TEST_F(ResumeEndToEndTest, DeletedTileIsPendingAndTruncatedTileIsRecomputed) {
  const std::string id = nlohmann::json::parse(ReadFileBytes(Tiles("a") / "manifest.json")).at("tiles").at(4);
  fs::path las;
  for (const auto& [tile, marker] : DoneMarkers(Tiles("a"))) {
    if (nlohmann::json::parse(marker).at("points").get<uint64_t>() > 1000 && tile != id)
      las = Tiles("a") / (tile + ".laz");
  }
  ASSERT_FALSE(las.empty());
  const std::string truncated_id = las.stem().string();
  // (d) delete one tile's LAS: status lists it as pending.
  const fs::path deleted = Tiles("a") / (id + ".laz");
  const bool had_las = fs::exists(deleted);
  if (had_las) fs::remove(deleted);
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config("a")), &out), 0) << out;
  if (had_las) {
    EXPECT_NE(out.find("pending  " + id), std::string::npos) << out;
  }
  // (e) truncate another: the next run recomputes both, and only them.
  fs::resize_file(las, fs::file_size(las) / 2);
  int code = 0;
  out = Run("a", "", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find((had_las ? "2" : "1") + std::string(" computed")), std::string::npos) << out;
  EXPECT_NE(out.find("tile " + truncated_id + " ("), std::string::npos) << out;
  ExpectFusedMatchesReference("a");
  ASSERT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config("a")), &out), 0) << out;
  EXPECT_NE(out.find(", 0 failed, 0 pending"), std::string::npos) << out;
}

// A tile whose DSM window or edge points were deleted is not done (its done marker records them): status lists it
// as pending and the next run recomputes it alone, giving the same DSM.
TEST_F(ResumeEndToEndTest, DeletedDsmFilesMakeTheirTilesPendingAndAreRecomputed) {
  std::string window_id, edge_id;
  for (const auto& [tile, marker] : DoneMarkers(Tiles("a"))) {
    for (const auto& p : nlohmann::json::parse(marker).value("products", nlohmann::json::array())) {
      const std::string suffix = p.at("suffix").get<std::string>();
      if (suffix == "dsm.tif" && window_id.empty()) window_id = tile;
      if (suffix == "dsm_edge.bin" && tile != window_id) edge_id = tile;
    }
  }
  ASSERT_FALSE(window_id.empty());
  ASSERT_FALSE(edge_id.empty());
  fs::remove(Tiles("a") / (window_id + ".dsm.tif"));
  fs::remove(Tiles("a") / (edge_id + ".dsm_edge.bin"));
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config("a")), &out), 0) << out;
  EXPECT_NE(out.find("pending  " + window_id), std::string::npos) << out;
  EXPECT_NE(out.find("pending  " + edge_id), std::string::npos) << out;
  int code = 0;
  out = Run("a", "", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("2 computed"), std::string::npos) << out;
  ExpectFusedMatchesReference("a");
}

// (f) A tile that throws (here: a folder squats on its LAS path, so the rename fails) gets a failed marker, the
// other tiles go on, the run exits 1 without merging (the previous fused.laz stays) and names the rerun command;
// fixing it and rerunning merges.
TEST_F(ResumeEndToEndTest, FailedTileIsRecordedAndTheOthersGoOn) {
  std::string id;  // a tile with points (an empty tile writes no LAS, so nothing would fail)
  for (const auto& [tile, marker] : DoneMarkers(Tiles("a"))) {
    if (nlohmann::json::parse(marker).at("points").get<uint64_t>() > 0) id = tile;
  }
  ASSERT_FALSE(id.empty());
  const fs::path las = Tiles("a") / (id + ".laz");
  fs::remove(las);
  fs::create_directories(las / "squatter");
  const std::string previous = ReadFileBytes(Out("a") / "fused.laz");
  const std::string previous_report = ReadFileBytes(Out("a") / "run_report.json");
  int code = 0;
  std::string out = Run("a", "", &code);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("sacfuse run " + Config("a").string() + " --tiles " + id), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(Tiles("a") / (id + ".failed.json")));
  // The previous complete outputs stay, byte for byte, and the run's state says it failed (status exits 1).
  EXPECT_TRUE(ReadFileBytes(Out("a") / "fused.laz") == previous);
  EXPECT_TRUE(ReadFileBytes(Out("a") / "run_report.json") == previous_report);
  EXPECT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config("a")), &out), 1) << out;
  EXPECT_NE(out.find("failed   " + id + ": "), std::string::npos) << out;
  EXPECT_NE(out.find("last run FAILED at "), std::string::npos) << out;
  EXPECT_NE(out.find("tiles failed (" + id + ")"), std::string::npos) << out;
  fs::remove_all(las);
  out = Run("a", " --tiles " + id, &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_FALSE(fs::exists(Tiles("a") / (id + ".failed.json")));
  ExpectFusedMatchesReference("a");
}

}  // namespace
}  // namespace sacfuse
