// End-to-end: the sacfuse binary as a user runs it — simulate a block, fuse it (union and SAC), score it; bad
// configs and corrupt inputs fail with clear messages and leave no partial fused.laz.
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/las_reader.h"
#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::RunCommand;
using testing::ShellQuote;
using testing::SacfuseBinary;
using testing::TempDir;

// One simulated tiny block shared by the tests of this file (simulation takes a few seconds).
class CliEndToEndTest : public testing::TinyBlockSuite {
 protected:
  // Writes a config fusing the block with `method` into `out_dir`; returns its path.
  static fs::path WriteConfig(const std::string& name, const std::string& method, const std::string& extra = "") {
    const fs::path path = Dir() / (name + ".yaml");
    std::ofstream(path) << "input: {format: colmap, path: " << Block().string() << "}\n"
                        << "output: {dir: " << (Dir() / name).string() << "}\n"
                        << "fusion:\n  method: " << method << "\n"
                        << extra
                        << "evaluation:\n  reference: " << (Block() / "reference.las").string() << "\n"
                        << "  mask: " << (Block() / "eval_mask.png").string() << "\n  gsd_m: " << BlockGsd() << "\n";
    return path;
  }
};

double F1FromJson(const fs::path& eval_json, size_t threshold_index) {
  return testing::EvalF1(eval_json, threshold_index);
}

TEST_F(CliEndToEndTest, SimulateWritesACompleteWorkspace) {
  for (const char* f : {"sparse/cameras.bin", "sparse/images.bin", "sparse/points3D.bin", "stereo/fusion.cfg",
                        "reference.las", "eval_mask.png", "eval_mask.json", "metadata.json", "sacfuse.yaml"}) {
    EXPECT_TRUE(fs::exists(Block() / f)) << f;
  }
}

TEST_F(CliEndToEndTest, SacBeatsTheUnionOnF1WithFewerPoints) {
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(WriteConfig("union", "union")), &out), 0) << out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(WriteConfig("sac", "sac")), &out), 0) << out;
  EXPECT_NE(out.find("fused cloud:"), std::string::npos) << out;
  EXPECT_NE(out.find("F1 @"), std::string::npos) << out;
  const fs::path u = Dir() / "union", s = Dir() / "sac";
  for (const fs::path& d : {u, s}) {
    for (const char* f : {"fused.laz", "sacfuse.effective.yaml", "run_report.json", "eval.json", "sacfuse.log"}) {
      EXPECT_TRUE(fs::exists(d / f)) << (d / f);
    }
  }
  const uint64_t union_points = LasReader((u / "fused.laz").string()).header().point_count;
  const uint64_t sac_points = LasReader((s / "fused.laz").string()).header().point_count;
  EXPECT_LT(sac_points, union_points * 85 / 100) << "SAC must remove at least 15% of the union's points";
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_GT(F1FromJson(s / "eval.json", t), F1FromJson(u / "eval.json", t)) << "threshold " << t;
  }
}

// The same acceptance on a block made from real airborne LiDAR (Zurich, LAStools sample), cropped to 60 m.
TEST(CliLidarTest, SacBeatsTheUnionOnALidarBlock) {
  const auto shared = testing::SharedDir();
  if (!shared) GTEST_SKIP() << "../shared research data not found (set SACFUSE_SHARED); skipping the LiDAR block";
  const fs::path las = *shared / "research-data" / "lidar" / "lastools" / "zurich.las";
  if (!fs::exists(las)) GTEST_SKIP() << las << " not found";
  TempDir dir;
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " simulate --preset tiny --seed 5 --area 60 --from-las " + ShellQuote(las) +
                           " --out " + ShellQuote(dir / "block"),
                       &out),
            0)
      << out;
  std::map<std::string, std::pair<uint64_t, std::vector<double>>> results;
  for (const std::string method : {"union", "sac"}) {
    const fs::path config = dir / (method + ".yaml");
    std::ofstream(config) << "input: {path: " << (dir / "block").string() << "}\noutput: {dir: "
                          << (dir / method).string() << "}\nfusion: {method: " << method << "}\n"
                          << "evaluation: {reference: " << (dir / "block" / "reference.las").string()
                          << ", mask: " << (dir / "block" / "eval_mask.png").string() << ", gsd_m: 0.2}\n";
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &out), 0) << out;
    results[method] = {LasReader((dir / method / "fused.laz").string()).header().point_count,
                       {F1FromJson(dir / method / "eval.json", 0), F1FromJson(dir / method / "eval.json", 1)}};
  }
  EXPECT_LT(results["sac"].first, results["union"].first * 85 / 100);
  for (size_t t = 0; t < 2; ++t) EXPECT_GT(results["sac"].second[t], results["union"].second[t]) << "threshold " << t;
}

// Strategy 1 (dense matching): the simulator writes COLMAP consistency graphs for tiny; SAC fuses with them.
TEST_F(CliEndToEndTest, DenseCorrespondencesFromConsistencyGraphs) {
  ASSERT_TRUE(fs::exists(Block() / "stereo" / "consistency_graphs"));
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " +
                           ShellQuote(WriteConfig("dense", "sac", "  correspondence: dense\n")),
                       &out),
            0)
      << out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(WriteConfig("union_for_dense", "union")), &out), 0) << out;
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_GT(F1FromJson(Dir() / "dense" / "eval.json", t),
              F1FromJson(Dir() / "union_for_dense" / "eval.json", t));
  }
}

TEST_F(CliEndToEndTest, SuperpixelsAreReusedOnASecondRun) {
  const fs::path config = WriteConfig("rerun", "sac");
  std::string first, second;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &first), 0) << first;
  EXPECT_NE(first.find("0 reused"), std::string::npos) << first;
  fs::copy_file(Dir() / "rerun" / "fused.laz", Dir() / "first.las");
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &second), 0) << second;
  EXPECT_NE(second.find("0 computed"), std::string::npos) << second;
  // Same result both times, byte for byte.
  EXPECT_EQ(testing::ReadFileBytes(Dir() / "first.las"),
            testing::ReadFileBytes(Dir() / "rerun" / "fused.laz"));
}

TEST_F(CliEndToEndTest, ConfigErrorsExitTwoAndNameKeyAndLine) {
  const fs::path path = Dir() / "bad.yaml";
  std::ofstream(path) << "input:\n  path: x\n  fromat: colmap\noutput: {scale_m: 0.003}\n";
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(path), &out), 2);
  EXPECT_NE(out.find("bad.yaml:3: input.fromat: unknown key"), std::string::npos) << out;
}

TEST_F(CliEndToEndTest, CorruptDepthMapFailsNamingTheFileAndLeavesNoLas) {
  // Copy the block and truncate one depth map.
  const fs::path copy = Dir() / "corrupt_block";
  fs::copy(Block(), copy, fs::copy_options::recursive);
  fs::path victim;
  for (const auto& e : fs::recursive_directory_iterator(copy / "stereo" / "depth_maps")) {
    if (e.is_regular_file()) {
      victim = e.path();
      break;
    }
  }
  ASSERT_FALSE(victim.empty());
  fs::resize_file(victim, fs::file_size(victim) / 2);
  const fs::path config = Dir() / "corrupt.yaml";
  std::ofstream(config) << "input: {path: " << copy.string() << "}\noutput: {dir: "
                        << (Dir() / "corrupt_out").string() << "}\n";
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &out), 1) << out;
  EXPECT_NE(out.find(victim.filename().string()), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(Dir() / "corrupt_out" / "fused.laz"));
  for (const auto& e : fs::directory_iterator(Dir() / "corrupt_out")) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "temporary file left: " << e.path();
  }
}

TEST_F(CliEndToEndTest, EvalCommandPrintsATableAndJson) {
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(WriteConfig("for_eval", "union")), &out), 0) << out;
  const fs::path json = Dir() / "eval_cmd.json";
  ASSERT_EQ(RunCommand(SacfuseBinary() + " eval " + ShellQuote(Dir() / "for_eval" / "fused.laz") + " --reference " +
                           ShellQuote(Block() / "reference.las") + " --gsd 0.1 --tau-gsd 2,5 --json " + ShellQuote(json),
                       &out),
            0)
      << out;
  EXPECT_NE(out.find("F1 @ 0.200 m"), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(json));
}

TEST(CliTest, PrintDefaultsIsAValidCompleteConfig) {
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run --print-defaults", &out), 0) << out;
  for (const char* key : {"input:", "format:", "output:", "scale_m:", "fusion:", "tau_m:", "superpixels:",
                          "evaluation:", "resources:", "# LAS coordinate quantum, metres"}) {
    EXPECT_NE(out.find(key), std::string::npos) << key;
  }
}

TEST(CliTest, HelpAndVersion) {
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " version", &out), 0);
  EXPECT_NE(out.find("sacfuse "), std::string::npos);
  for (const char* cmd : {"run", "simulate", "eval"}) {
    EXPECT_EQ(RunCommand(SacfuseBinary() + " " + cmd + " --help", &out), 0) << cmd;
    EXPECT_NE(out.find("--"), std::string::npos) << cmd;
  }
  EXPECT_EQ(RunCommand(SacfuseBinary() + " frobnicate", &out), 2);
}

}  // namespace
}  // namespace sacfuse
