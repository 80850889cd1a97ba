// End-to-end: one output folder, one writer (issue 50), on the tiny block (seed 3, 20 m tiles). Races are made
// deterministic with io/test_pause.h: a process is held at a named point while the test acts. Each race asserts
// that the cloud equals a fresh run's or that the loser refuses, naming the holder:
//  - while a run writes the folder: a second run (another config, and the same config), a merge and a `tile`
//    worker of another config are refused; a worker of the same config is served; `run --wait` waits and then
//    finds every tile done; the cloud equals a fresh run's;
//  - while a merge writes: a run is refused; a worker's start-up clean-up leaves the merge's temporary cloud; a
//    tile marker rewritten during the merge fails it (nothing written);
//  - a writer killed with SIGKILL: `status` says it was interrupted; the next run starts at once, removes its
//    temporary files and gives a fresh run's cloud;
//  - two `tile` workers on one tile: the second leaves it to the first (named), which computes it;
//  - tiles of another config (a worker without any writer in the folder) are never merged: `merge` refuses naming
//    the tile, `status` says the cloud is not the merge of the present tiles, the next run recomputes that tile;
//  - an input edited during a run fails it before the merge (tiled) or the rename (untiled), naming the file;
//  - paths with bytes that are not UTF-8, an output.format switch (the other format's cloud removed, `status`
//    names the right file), a COLMAP model without sparse points (heights from the depth maps, with a warning).
#include <signal.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/process_identity.h"
#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::BackgroundCommand;
using testing::ReadFileBytes;
using testing::ReadJsonFile;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;
using testing::WaitForFile;
using testing::WithoutLasCreationDate;

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class OneWriterEndToEndTest : public testing::TinyBlockSuite {
 protected:
  // One fresh run of config "a"; the cases start from copies of its folder (a copied folder resumes: its tiles
  // verify), which keeps the suite to one full run.
  static void SetUpTestSuite() {
    SimulateBlock();
    WriteConfig("fresh_a", "fresh_a");
    std::string out;
    ASSERT_EQ(Run("run " + ShellQuote(Config("fresh_a")), &out), 0) << out;
    fresh_cloud_ = new std::string(WithoutLasCreationDate(ReadFileBytes(Out("fresh_a") / "fused.laz")));
  }
  static void TearDownTestSuite() {
    delete fresh_cloud_;
    fresh_cloud_ = nullptr;
    TinyBlockSuite::TearDownTestSuite();
  }
  // A copy of the fresh run's folder (times kept: `cp -a`).
  static void CopyFreshOutput(const std::string& out) {
    ASSERT_EQ(RunCommand("cp -a " + ShellQuote(Out("fresh_a")) + " " + ShellQuote(Out(out))), 0);
  }
  static inline std::string* fresh_cloud_ = nullptr;
  // A tiled config of the tiny block into `out`; `other_settings` adds the result-affecting keys of the issue's
  // second config.
  static fs::path WriteConfig(const std::string& name, const std::string& out, bool other_settings = false,
                              const std::string& block = "", const std::string& format = "laz") {
    std::ofstream(Config(name)) << "input: {path: " << (block.empty() ? Block().string() : block) << "}\n"
                                << "output: {dir: " << Out(out).string() << ", format: " << format << "}\n"
                                << "tiling: {tile_size_m: 20, halo_m: 5}\n"
                                << (other_settings ? "fusion: {tau_m: 1.0, min_consistent_views: 3}\n" : "");
    return Config(name);
  }
  static std::string Sacfuse(const std::string& args) { return SacfuseBinary() + " " + args; }
  static int Run(const std::string& args, std::string* out) { return RunCommand(Sacfuse(args), out); }
  // SACFUSE_TEST_PAUSE for one point, its file in the suite's folder.
  static std::vector<std::string> PauseAt(const std::string& point, const fs::path& file) {
    return {"SACFUSE_TEST_PAUSE=" + point + "=" + file.string()};
  }
  static void ExpectFreshCloudA(const std::string& out) {
    const std::string cloud = WithoutLasCreationDate(ReadFileBytes(Out(out) / "fused.laz"));
    EXPECT_GT(cloud.size(), 100000u) << out;
    EXPECT_TRUE(fresh_cloud_ != nullptr && cloud == *fresh_cloud_) << out << ": fused.laz differs from a fresh run's";
  }
  static std::string Pid(const fs::path& pause_file) {
    std::string pid = ReadFileBytes(pause_file);
    return pid.substr(0, pid.find('\n'));
  }
};

// Defects 1 and 2 of issue 50: a second run on a folder in use merged tiles of two configs (or deleted the live
// run's temporary cloud). Now the folder has one writer; the others are refused, naming it.
TEST_F(OneWriterEndToEndTest, WhileARunWritesTheFolderOtherWritersAndForeignWorkersAreRefused) {
  const fs::path a = WriteConfig("race_a", "race"), b = WriteConfig("race_b", "race", /*other_settings=*/true);
  CopyFreshOutput("race");
  const fs::path pause = Dir() / "pause_race";
  BackgroundCommand run_a(Sacfuse("run " + ShellQuote(a)), PauseAt("run:before_merge", pause));
  ASSERT_TRUE(WaitForFile(pause)) << "run A did not reach the merge";
  const std::string holder = "`sacfuse run` (pid " + Pid(pause) + " on host ";
  std::string out;
  EXPECT_EQ(Run("run " + ShellQuote(b), &out), 1) << out;
  EXPECT_TRUE(Has(out, holder) && Has(out, "is writing this output folder; one output folder has one writer")) << out;
  EXPECT_EQ(Run("run " + ShellQuote(a), &out), 1) << out;  // the same config too (its clean-up was defect 2)
  EXPECT_TRUE(Has(out, holder)) << out;
  EXPECT_EQ(Run("merge " + ShellQuote(a), &out), 1) << out;
  EXPECT_TRUE(Has(out, holder)) << out;
  // The refused ones left the run's state alone.
  EXPECT_EQ(ReadJsonFile(Out("race") / "run_state.json").at("pid").get<int64_t>(), std::stoll(Pid(pause)));
  EXPECT_EQ(Run("status " + ShellQuote(a), &out), 0) << out;
  EXPECT_TRUE(Has(out, "now writing " + Out("race").string() + ": " + holder)) << out;
  // A worker of another config is refused; one of the run's config is served (its tile is done).
  EXPECT_EQ(Run("tile " + ShellQuote(b) + " --id 2_2", &out), 1) << out;
  EXPECT_TRUE(Has(out, holder) && Has(out, "with other result-affecting settings (config hash ")) << out;
  EXPECT_EQ(Run("tile " + ShellQuote(a) + " --id 2_2", &out), 0) << out;
  EXPECT_TRUE(Has(out, "tile 2_2: done, skipped")) << out;
  // A second run of the same config that waits starts when the first is done and finds every tile done.
  BackgroundCommand waiting(Sacfuse("run --wait " + ShellQuote(a)));
  ASSERT_TRUE(waiting.WaitForOutput("waiting for " + holder)) << waiting.Output();
  fs::remove(pause);
  ASSERT_EQ(run_a.Wait(&out), 0) << out;
  ExpectFreshCloudA("race");
  ASSERT_EQ(waiting.Wait(&out), 0) << out;
  EXPECT_TRUE(Has(out, "tiles: 0 computed")) << out;
  ExpectFreshCloudA("race");

  // A merge holds the folder too: a run is refused while it writes; a tile rewritten during it fails it.
  const fs::path merge_pause = Dir() / "pause_merge";
  BackgroundCommand merge(Sacfuse("merge " + ShellQuote(a)), PauseAt("merge:before_commit", merge_pause));
  ASSERT_TRUE(WaitForFile(merge_pause)) << "the merge did not reach its commit";
  EXPECT_EQ(Run("run " + ShellQuote(a), &out), 1) << out;
  EXPECT_TRUE(Has(out, "`sacfuse merge` (pid " + Pid(merge_pause) + " on host ")) << out;
  // The merge's half-written cloud is a temporary file of a live process: a worker starting now (its start-up
  // clean-up runs) leaves it alone.
  const std::string merge_temp = "fused.laz.tmp-" + ThisHostName() + "-" + Pid(merge_pause) + "-";
  ASSERT_EQ(testing::CountFilesNamedWith(Out("race"), merge_temp), 1u);
  EXPECT_EQ(Run("tile " + ShellQuote(a) + " --id 2_2", &out), 0) << out;
  EXPECT_EQ(testing::CountFilesNamedWith(Out("race"), merge_temp), 1u) << out;
  const fs::path marker = Out("race") / "tiles" / "2_2.done.json";
  nlohmann::json m = ReadJsonFile(marker);
  m["finished_unix_ns"] = m.at("finished_unix_ns").get<int64_t>() + 1;
  std::ofstream(marker) << m.dump(2) << "\n";
  const std::string before = ReadFileBytes(Out("race") / "fused.laz");
  fs::remove(merge_pause);
  EXPECT_EQ(merge.Wait(&out), 1) << out;
  EXPECT_TRUE(Has(out, "tile 2_2 was rewritten by another process during the merge")) << out;
  EXPECT_TRUE(ReadFileBytes(Out("race") / "fused.laz") == before);
  EXPECT_EQ(testing::CountFilesNamedWith(Out("race"), ".tmp-"), 0u);
}

// kill -9 of a run that holds the folder: the kernel releases the lock, `status` says the run was interrupted, and
// the next run starts at once, removes the killed run's temporary files and gives a fresh run's cloud.
TEST_F(OneWriterEndToEndTest, KilledWriterLeavesTheFolderToTheNextRun) {
  const fs::path a = WriteConfig("killed", "killed");
  CopyFreshOutput("killed");
  const fs::path pause = Dir() / "pause_killed";
  BackgroundCommand run(Sacfuse("run " + ShellQuote(a)), PauseAt("run:started", pause));
  ASSERT_TRUE(WaitForFile(pause));
  const std::string pid = Pid(pause);
  const fs::path left = Out("killed") / ("fused.laz.tmp-" + ThisHostName() + "-" + pid + "-0");
  std::ofstream(left) << "half-written by the killed run";
  ASSERT_EQ(::kill(static_cast<pid_t>(std::stoll(pid)), SIGKILL), 0);
  std::string out;
  run.Wait(&out);
  fs::remove(pause);
  EXPECT_EQ(ReadJsonFile(Out("killed") / "run_state.json").at("status"), "running");
  EXPECT_EQ(Run("status " + ShellQuote(a), &out), 1) << out;
  EXPECT_TRUE(Has(out, "last run (pid " + pid + ", started ") && Has(out, ") was INTERRUPTED: its process is gone"))
      << out;
  ASSERT_EQ(Run("run " + ShellQuote(a), &out), 0) << out;
  EXPECT_TRUE(Has(out, "removed " + left.string() + " (left by a process that is gone)")) << out;
  EXPECT_FALSE(fs::exists(left));
  ExpectFreshCloudA("killed");
}

// Two `tile` workers on one tile: the second leaves it to the first, naming it; the first computes it; the merge
// gives a fresh run's cloud.
TEST_F(OneWriterEndToEndTest, TileWorkersRacingOnOneTileComputeItOnce) {
  const fs::path a = WriteConfig("workers", "workers");
  CopyFreshOutput("workers");
  std::string out;
  fs::remove(Out("workers") / "tiles" / "2_3.done.json");  // the tile is to be computed again
  const fs::path pause = Dir() / "pause_worker";
  BackgroundCommand first(Sacfuse("tile " + ShellQuote(a) + " --id 2_3"), PauseAt("tile:claimed", pause));
  ASSERT_TRUE(WaitForFile(pause));
  EXPECT_EQ(Run("tile " + ShellQuote(a) + " --id 2_3", &out), 0) << out;
  EXPECT_TRUE(Has(out, "tile 2_3: claimed by ") && Has(out, " pid " + Pid(pause) + " since ")) << out;
  EXPECT_TRUE(Has(out, "skipped")) << out;
  fs::remove(pause);
  ASSERT_EQ(first.Wait(&out), 0) << out;
  EXPECT_TRUE(Has(out, "tile 2_3: computed")) << out;
  ASSERT_EQ(Run("merge " + ShellQuote(a), &out), 0) << out;
  ExpectFreshCloudA("workers");
}

// The second line of defence, which holds without any lock: a tile computed with another config (a worker with no
// writer in the folder) is never merged; `status` tells the truth about the cloud; the next run recomputes it.
TEST_F(OneWriterEndToEndTest, TilesOfAnotherConfigAreNeverMerged) {
  const fs::path a = WriteConfig("mixed_a", "mixed"), b = WriteConfig("mixed_b", "mixed", /*other_settings=*/true);
  CopyFreshOutput("mixed");
  std::string out;
  ASSERT_EQ(Run("tile " + ShellQuote(b) + " --id 3_3", &out), 0) << out;  // no writer: allowed, it is B's tile now
  EXPECT_TRUE(Has(out, "tile 3_3: computed")) << out;
  const std::string before = ReadFileBytes(Out("mixed") / "fused.laz");
  EXPECT_EQ(Run("merge " + ShellQuote(a), &out), 1) << out;
  EXPECT_TRUE(Has(out, "1 tiles are not done; nothing merged. Missing: 3_3")) << out;
  EXPECT_TRUE(ReadFileBytes(Out("mixed") / "fused.laz") == before);
  EXPECT_EQ(Run("status " + ShellQuote(a), &out), 0) << out;
  EXPECT_TRUE(Has(out, "pending  3_3 (computed with another config)")) << out;
  EXPECT_TRUE(Has(out, "by an earlier merge; 1 of ")) << out;
  EXPECT_TRUE(Has(out, " tiles are not done now, so it is not the merge of the present tiles")) << out;
  ASSERT_EQ(Run("run " + ShellQuote(a), &out), 0) << out;
  EXPECT_TRUE(Has(out, "tiles: 1 computed")) << out;
  ExpectFreshCloudA("mixed");
  EXPECT_EQ(Run("status " + ShellQuote(a), &out), 0) << out;
  EXPECT_TRUE(Has(out, "fused.laz: merged from the ")) << out;
}

// Defect 5: a depth map edited during a run (after the tiles, before the merge) made a cloud that matched neither
// input. The run now fails naming the file and keeps the previous cloud (that the next run recomputes what the
// change affects is tests/run_state_e2e_test.cc's).
TEST_F(OneWriterEndToEndTest, InputEditedDuringARunFailsItNamingTheFile) {
  const fs::path block = Dir() / "block_edited";
  ASSERT_EQ(RunCommand("cp -a " + ShellQuote(Block()) + " " + ShellQuote(block)), 0);  // times kept: tiles verify
  const fs::path a = WriteConfig("edited", "edited", false, block.string());
  CopyFreshOutput("edited");
  const std::string before = ReadFileBytes(Out("edited") / "fused.laz");
  const fs::path depth = block / "stereo/depth_maps/nadir/0010.jpg.geometric.bin";
  ASSERT_TRUE(fs::exists(depth));
  const fs::path pause = Dir() / "pause_edit";
  BackgroundCommand run(Sacfuse("run " + ShellQuote(a)), PauseAt("run:before_merge", pause));
  ASSERT_TRUE(WaitForFile(pause));
  std::string bytes = ReadFileBytes(depth);
  bytes[bytes.size() - 1] ^= 0x01;  // the last depth of the map, a little different
  std::ofstream(depth, std::ios::binary | std::ios::trunc) << bytes;
  fs::remove(pause);
  std::string out;
  EXPECT_EQ(run.Wait(&out), 1) << out;
  EXPECT_TRUE(Has(out, depth.string() + ": depth map changed (size ")) << out;
  EXPECT_TRUE(Has(out, "during this run (view ") && Has(out, "the fused cloud was not written")) << out;
  EXPECT_TRUE(ReadFileBytes(Out("edited") / "fused.laz") == before);  // the previous cloud stays
  EXPECT_EQ(ReadJsonFile(Out("edited") / "run_state.json").at("status"), "failed");
  EXPECT_EQ(Run("status " + ShellQuote(a), &out), 1) << out;
  EXPECT_TRUE(Has(out, "last run FAILED at ") && Has(out, "depth map changed")) << out;
}

// Defect 5 without tiles: the whole fusion is the window. The untiled run checks its inputs again before the cloud
// is renamed into place; an edited depth map fails it, naming the file, and no cloud is written.
TEST_F(OneWriterEndToEndTest, InputEditedDuringAnUntiledRunFailsItNamingTheFile) {
  const fs::path block = Dir() / "block_edited_untiled";
  ASSERT_EQ(RunCommand("cp -a " + ShellQuote(Block()) + " " + ShellQuote(block)), 0);
  std::ofstream(Config("untiled")) << "input: {path: " << block.string() << "}\noutput: {dir: "
                                   << Out("untiled").string() << "}\ncoregistration: {enabled: false}\n";
  const fs::path depth = block / "stereo/depth_maps/nadir/0010.jpg.geometric.bin";
  const fs::path pause = Dir() / "pause_untiled";
  BackgroundCommand run(Sacfuse("run " + ShellQuote(Config("untiled"))), PauseAt("run:before_commit", pause));
  ASSERT_TRUE(WaitForFile(pause));
  std::string bytes = ReadFileBytes(depth);
  bytes[bytes.size() - 1] ^= 0x01;
  std::ofstream(depth, std::ios::binary | std::ios::trunc) << bytes;
  fs::remove(pause);
  std::string out;
  EXPECT_EQ(run.Wait(&out), 1) << out;
  EXPECT_TRUE(Has(out, depth.string() + ": depth map changed (size ")) << out;
  EXPECT_TRUE(Has(out, "untiled")) << out;  // it was the untiled path
  EXPECT_FALSE(fs::exists(Out("untiled") / "fused.laz"));
  EXPECT_EQ(testing::CountFilesNamedWith(Out("untiled"), ".tmp-"), 0u);
}

// Defects 4, 7 and 8 (status): an output folder whose path holds a byte that is not UTF-8 works end to end (the
// JSON files carry U+FFFD in its place); switching output.format removes the other format's cloud; `status` names
// the cloud of the configured format.
TEST_F(OneWriterEndToEndTest, NonUtf8PathsAndFormatSwitch) {
  const std::string name = "out\xff";
  WriteConfig("bytes_laz", name);
  WriteConfig("bytes_las", name, false, "", "las");
  CopyFreshOutput(name);
  std::string out;
  ASSERT_EQ(Run("run " + ShellQuote(Config("bytes_laz")), &out), 0) << out;
  const nlohmann::json report = ReadJsonFile(Out(name) / "run_report.json");
  EXPECT_TRUE(Has(report.at("fused_las").get<std::string>(), "out\xef\xbf\xbd/fused.laz")) << report.dump();
  EXPECT_EQ(ReadJsonFile(Out(name) / "run_state.json").at("status"), "succeeded");
  EXPECT_EQ(Run("status " + ShellQuote(Config("bytes_laz")), &out), 0) << out;
  EXPECT_TRUE(Has(out, "fused.laz: merged from the ")) << out;
  EXPECT_FALSE(Has(out, "fused.las")) << out;
  ASSERT_EQ(Run("run " + ShellQuote(Config("bytes_las")), &out), 0) << out;
  EXPECT_TRUE(Has(out, "removed " + (Out(name) / "fused.laz").string() +
                           ": the cloud of an earlier run with output.format laz"))
      << out;
  EXPECT_FALSE(fs::exists(Out(name) / "fused.laz"));
  EXPECT_TRUE(fs::exists(Out(name) / "fused.las"));
  EXPECT_EQ(Run("status " + ShellQuote(Config("bytes_las")), &out), 0) << out;
  EXPECT_TRUE(Has(out, "fused.las: merged from the ")) << out;
  std::ofstream(Out(name) / "fused.laz") << "left by an older version";
  EXPECT_EQ(Run("status " + ShellQuote(Config("bytes_las")), &out), 0) << out;
  EXPECT_TRUE(Has(out, "fused.laz: left by an earlier run with output.format laz; not this config's output")) << out;
}

// Defect 3: with an empty points3D.bin the plan fell back to the config's z range [0, 100] m (the scene spans
// 99-134 m): many more tiles, an incomplete cloud, no warning. The heights now come from the depth maps, with a
// warning in the log, run_report.json and the HTML report, and the plan has the tiles of the sparse model's.
TEST_F(OneWriterEndToEndTest, ModelWithoutSparsePointsTakesHeightsFromTheDepthMaps) {
  const fs::path block = Dir() / "block_nopoints";
  fs::copy(Block(), block, fs::copy_options::recursive);
  const uint64_t zero = 0;
  std::ofstream(block / "sparse/points3D.bin", std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(&zero), sizeof(zero));
  for (const auto& [config, out, input] : {std::tuple<std::string, std::string, fs::path>{"sparse", "plan_sparse", Block()},
                                           {"nopoints", "plan_nopoints", block}}) {
    std::ofstream(Config(config)) << "input: {path: " << input.string() << "}\noutput: {dir: " << Out(out).string()
                                  << "}\ntiling: {tile_size_m: 20, halo_m: 5}\ncoregistration: {enabled: false}\n";
  }
  std::string sparse, nopoints;
  ASSERT_EQ(Run("plan --list " + ShellQuote(Config("sparse")), &sparse), 0) << sparse;
  ASSERT_EQ(Run("run " + ShellQuote(Config("nopoints")), &nopoints), 0) << nopoints;
  const std::string warning = "points3D.bin: the sparse model has no points; the block's height range is taken from ";
  EXPECT_TRUE(Has(nopoints, warning)) << nopoints;
  // The warning is in the run's report too, and at the top of the HTML report.
  const nlohmann::json warnings = ReadJsonFile(Out("plan_nopoints") / "run_report.json").at("warnings");
  ASSERT_EQ(warnings.size(), 1u) << warnings;
  EXPECT_TRUE(Has(warnings[0].get<std::string>(), warning)) << warnings;
  EXPECT_TRUE(Has(ReadFileBytes(Out("plan_nopoints") / "report/index.html"), "<b>Input:</b> ")) << "no input warning";
  const nlohmann::json a = ReadJsonFile(Out("plan_sparse") / "plan.json");
  const nlohmann::json b = ReadJsonFile(Out("plan_nopoints") / "plan.json");
  EXPECT_EQ(b.at("z_source"), "depth-map sample (the sparse model has no points)");
  // The same grid; the depth maps' range is within 2 m of the sparse points' (the config's was [0, 100] m), and
  // every tile with views in the sparse model's plan has views in this one (the sample reaches a little wider).
  EXPECT_EQ(b.at("grid"), a.at("grid"));
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(b.at("z_range_m")[i].get<double>(), a.at("z_range_m")[i].get<double>(), 2.0) << b.at("z_range_m");
  }
  ASSERT_EQ(a.at("tiles").size(), b.at("tiles").size());
  for (size_t t = 0; t < a.at("tiles").size(); ++t) {
    if (!a.at("tiles")[t].at("views").empty()) EXPECT_FALSE(b.at("tiles")[t].at("views").empty()) << t;
  }
}

}  // namespace
}  // namespace sacfuse
