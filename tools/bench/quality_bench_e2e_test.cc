// End-to-end: `sacfuse bench --quick` on a simulated tiny block (expected rows, the ceiling above every method,
// union denser than SAC, resume re-runs nothing), missing LiDAR files and a missing aerial-bench folder skipped
// with a message, and a failing COLMAP recorded as failed rows while the bench goes on.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/block_suite.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadJsonFile;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// `sacfuse bench` of our zurich block (no ablations, no COLMAP) and the given aerial-bench blocks; its exit code.
int BenchWithAerial(const fs::path& lidar, const fs::path& aerial_bench, const std::string& aerial_blocks,
                    const fs::path& out, std::string* log) {
  return RunCommand(SacfuseBinary() + " bench --blocks zurich --no-ablations --colmap off --lidar-dir " +
                        ShellQuote(lidar) + " --aerial-bench " + ShellQuote(aerial_bench) + " --aerial-blocks " +
                        aerial_blocks + " --out " + ShellQuote(out),
                    log);
}

// The scenes bench.json lists as skipped.
std::set<std::string> SkippedScenes(const nlohmann::json& bench) {
  std::set<std::string> skipped;
  for (const auto& b : bench["blocks"]) {
    if (b["status"] == "skipped") skipped.insert(b["scene"].get<std::string>());
  }
  return skipped;
}

TEST(QualityBenchEndToEndTest, QuickBenchHasTheRowsAndResumes) {
  testing::TempDir dir;
  const fs::path out = dir / "bench";
  const std::string command = SacfuseBinary() + " bench --quick --out " + ShellQuote(out);
  std::string log;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(RunCommand(command, &log), 0) << log;
  const double first_s = Seconds(start);
  EXPECT_NE(log.find("city scale 1 | tsdf: F1 "), std::string::npos) << "progress per row: " << log;

  const nlohmann::json j = ReadJsonFile(out / "bench.json");
  std::vector<std::string> names;
  for (const auto& r : j["rows"]) names.push_back(r["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"sac", "union", "tsdf", "ceiling (union, no errors)", "sac (default)",
                                             "sac, fusion.unary: paper"}));
  EXPECT_EQ(j["failed_rows"], 0);
  double ceiling = -1;
  std::map<std::string, const nlohmann::json*> main;
  for (const auto& r : j["rows"]) {
    EXPECT_EQ(r["status"], "ok") << r.dump();
    if (r["section"] != "main") continue;
    main[r["name"]] = &r;
    if (r["is_ceiling"].get<bool>()) ceiling = r["f1_2gsd_pct"].get<double>();
    EXPECT_GT(r["wall_s"].get<double>(), 0.0);
    EXPECT_GT(r["peak_rss_mib"].get<double>(), 0.0);
    EXPECT_GT(r["redundancy"].get<double>(), 0.0);
  }
  for (const auto& [name, r] : main) {
    EXPECT_GE(ceiling, (*r)["f1_2gsd_pct"].get<double>()) << name << " above the ceiling";
  }
  EXPECT_GT((*main["union"])["points"].get<uint64_t>(), (*main["sac"])["points"].get<uint64_t>());
  EXPECT_GT((*main["union"])["redundancy"].get<double>(), (*main["sac"])["redundancy"].get<double>());
  ASSERT_EQ(j["summaries"].size(), 2u);
  EXPECT_GE(j["summaries"][0]["sac_rank_2gsd"].get<int>(), 1);
  EXPECT_EQ(j["summaries"][0]["ranked"], 3);
  const std::string md = testing::ReadFileBytes(out / "bench.md");
  EXPECT_NE(md.find("| **sac** |"), std::string::npos) << md;
  EXPECT_NE(md.find("### Average over blocks"), std::string::npos) << md;
  EXPECT_NE(md.find("## Ablations"), std::string::npos) << md;
  // The row's clouds are gone once scored; its config and scores stay.
  const fs::path tsdf_dir = out / main["tsdf"]->at("folder").get<std::string>();
  EXPECT_TRUE(fs::exists(tsdf_dir / "eval.json"));
  EXPECT_TRUE(fs::exists(tsdf_dir / "sacfuse.yaml"));
  EXPECT_FALSE(fs::exists(tsdf_dir / "out" / "fused.las"));

  // Second run: every row and block is reused.
  const auto again = std::chrono::steady_clock::now();
  ASSERT_EQ(RunCommand(command, &log), 0) << log;
  const double second_s = Seconds(again);
  EXPECT_EQ(log.find("simulating"), std::string::npos) << log;
  const nlohmann::json k = ReadJsonFile(out / "bench.json");
  for (const auto& r : k["rows"]) EXPECT_TRUE(r["reused"].get<bool>()) << r.dump();
  EXPECT_EQ(k["rows"][2]["f1_2gsd_pct"], j["rows"][2]["f1_2gsd_pct"]);
  EXPECT_LT(second_s, first_s / 3) << "first " << first_s << " s, second " << second_s << " s";
  std::cout << "bench --quick: " << first_s << " s; rerun " << second_s << " s\n";
}

TEST(QualityBenchEndToEndTest, MissingLidarFilesAreSkippedWithAMessage) {
  testing::TempDir dir;
  const fs::path out = dir / "bench";
  std::string log;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " bench --blocks zurich,semis --no-ablations --colmap off --aerial-bench off "
                                         "--lidar-dir " +
                           ShellQuote(dir / "nolidar") + " --out " + ShellQuote(out),
                       &log),
            0)
      << log;
  EXPECT_NE(log.find("skipping block zurich: LiDAR file not found: " + (dir / "nolidar").string() +
                     "/lastools/zurich.las"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("skipping block semis"), std::string::npos) << log;
  const nlohmann::json j = ReadJsonFile(out / "bench.json");
  EXPECT_TRUE(j["rows"].empty());
  EXPECT_EQ(SkippedScenes(j), (std::set<std::string>{"zurich", "semis"}));
  EXPECT_NE(testing::ReadFileBytes(out / "bench.md").find("skipped block zurich"), std::string::npos);
}

TEST(QualityBenchEndToEndTest, MissingAerialBenchIsSkippedWithAMessage) {
  testing::TempDir dir;
  const fs::path out = dir / "bench";
  std::string log;
  ASSERT_EQ(BenchWithAerial(dir / "nolidar", dir / "noab", "montpellier,zurich_e25", out, &log), 0) << log;
  const std::string message = "aerial-bench not found: " + (dir / "noab" / "make_block.py").string() + " is missing";
  EXPECT_NE(log.find("skipping block aerial montpellier: " + message), std::string::npos) << log;
  EXPECT_NE(log.find("skipping block aerial zurich_e25: " + message), std::string::npos) << log;
  const nlohmann::json j = ReadJsonFile(out / "bench.json");
  EXPECT_TRUE(j["aerial_rows"].empty());
  EXPECT_EQ(SkippedScenes(j), (std::set<std::string>{"zurich", "aerial montpellier", "aerial zurich_e25"}));
  EXPECT_NE(testing::ReadFileBytes(out / "bench.md").find("skipped block aerial montpellier"), std::string::npos);
}

// A make_block.py that fails: the block's rows are recorded as failed with its log, the next block still runs.
TEST(QualityBenchEndToEndTest, FailingAerialBlockIsRecordedAndTheBenchGoesOn) {
  testing::TempDir dir;
  fs::create_directories(dir / "ab");
  std::ofstream(dir / "ab" / "make_block.py") << "import sys\nprint('fake make_block failure', file=sys.stderr)\n"
                                                 "sys.exit(3)\n";
  fs::create_directories(dir / "lidar" / "lastools");
  std::ofstream(dir / "lidar" / "lastools" / "zurich.las") << "x";
  const fs::path out = dir / "bench";
  std::string log;
  EXPECT_EQ(BenchWithAerial(dir / "lidar", dir / "ab", "zurich,zurich_e25", out, &log), 1) << log;
  EXPECT_NE(log.find("making aerial-bench block zurich_e25"), std::string::npos) << "the bench went on: " << log;
  const nlohmann::json j = ReadJsonFile(out / "bench.json");
  ASSERT_EQ(j["aerial_rows"].size(), 8u) << j.dump(1);  // sacfuse, tsdf, union, oracle on each block
  for (const auto& r : j["aerial_rows"]) {
    EXPECT_EQ(r["status"], "failed");
    EXPECT_NE(r["error"].get<std::string>().find("fake make_block failure"), std::string::npos) << r;
  }
  int failed_main = 0;  // the fake zurich.las fails our own zurich block too
  for (const auto& r : j["rows"]) failed_main += r["status"] == "failed" ? 1 : 0;
  EXPECT_EQ(j["failed_rows"], 8 + failed_main);
  EXPECT_NE(testing::ReadFileBytes(out / "bench.md").find("- aerial-bench / zurich / sacfuse: "), std::string::npos);
}

// COLMAP rows off, but the block's peers.json has COLMAP's row from an earlier run: it is shown (reused), so the
// best peer and the half-way line are judged against it; no aerial-bench script runs (they would fail).
TEST(QualityBenchEndToEndTest, ColmapRowOfPeersJsonIsShownWithColmapOff) {
  testing::TempDir dir;
  fs::create_directories(dir / "ab");
  for (const char* script : {"make_block.py", "peers.py", "score.py"}) {
    std::ofstream(dir / "ab" / script) << "import sys\nsys.exit(3)\n";
  }
  fs::create_directories(dir / "lidar" / "lastools");
  std::ofstream(dir / "lidar" / "lastools" / "zurich.las") << "x";
  const fs::path block = dir / "bench" / "aerial" / "zurich";
  fs::create_directories(block);
  std::ofstream(block / "meta.json") << "{}";
  const auto peer = [](const std::string& method, double f1) {
    nlohmann::json score = {{"protocol", "v2"}, {"gsd", 0.125}, {"thresholds", {0.25, 0.625}},
                            {"points_in_mask", 1000}, {"density_per_m2", 10.0},
                            {"scores", {{{"tau", 0.25}, {"f1", f1}}, {{"tau", 0.625}, {"f1", 0.99}}}},
                            {"diagnostics_v2", {{"tau", 0.25}, {"above_top", 0.01}}}};
    return nlohmann::json{{"method", method}, {"returncode", 0}, {"wall_s", 1.0}, {"peak_rss_mb", 10.0},
                          {"score", score}};
  };
  nlohmann::json peers = {{"gsd", 0.125}, {"peers", nlohmann::json::array()}};
  peers["peers"] = {peer("colmap_best", 0.90), peer("tsdf", 0.80), peer("union", 0.70), peer("oracle", 0.95)};
  std::ofstream(block / "peers.json") << peers.dump();
  std::string log;
  BenchWithAerial(dir / "lidar", dir / "ab", "zurich", dir / "bench", &log);  // sacfuse's row fails: fake block
  EXPECT_EQ(log.find("aerial-bench peers on"), std::string::npos) << "peers.py ran: " << log;
  const nlohmann::json j = ReadJsonFile(dir / "bench" / "bench.json");
  std::map<std::string, nlohmann::json> rows;
  for (const auto& r : j["aerial_rows"]) rows[r["method"].get<std::string>()] = r;
  ASSERT_EQ(rows.size(), 5u) << j["aerial_rows"].dump(1);
  EXPECT_EQ(rows.at("colmap_best")["status"], "ok");
  EXPECT_EQ(rows.at("colmap_best")["reused"], true);
  EXPECT_DOUBLE_EQ(rows.at("colmap_best")["f1_2gsd_pct"].get<double>(), 90.0);
  EXPECT_EQ(rows.at("sacfuse")["status"], "failed");
  // Without COLMAP's row in peers.json, --colmap off shows none.
  peers["peers"].erase(0);
  std::ofstream(block / "peers.json") << peers.dump();
  BenchWithAerial(dir / "lidar", dir / "ab", "zurich", dir / "bench", &log);
  const nlohmann::json k = ReadJsonFile(dir / "bench" / "bench.json");
  size_t colmap_rows = 0;
  for (const auto& r : k["aerial_rows"]) colmap_rows += r["method"] == "colmap_best" ? 1 : 0;
  EXPECT_EQ(colmap_rows, 0u);
  EXPECT_EQ(k["aerial_rows"].size(), 4u);
}

TEST(QualityBenchEndToEndTest, FailingRowsAreRecordedAndTheBenchGoesOn) {
  testing::TempDir dir;
  const fs::path fake = dir / "fake_colmap";
  {
    std::ofstream(fake) << "#!/bin/sh\n"
                           "if [ \"$1\" = -h ]; then echo 'COLMAP 0.0 -- fake'; exit 0; fi\n"
                           "echo 'F0101 fake failure' >&2; exit 3\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  const fs::path out = dir / "bench";
  std::string log;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " bench --quick --methods union --no-ablations --colmap " +
                           ShellQuote(fake) + " --out " + ShellQuote(out),
                       &log),
            1)
      << "a failed row makes the exit code non-zero: " << log;
  EXPECT_NE(log.find("FAILED"), std::string::npos) << log;
  const nlohmann::json j = ReadJsonFile(out / "bench.json");
  ASSERT_EQ(j["rows"].size(), 4u) << j.dump(1);  // union, 2 x COLMAP, ceiling
  EXPECT_EQ(j["rows"][0]["status"], "ok");
  EXPECT_EQ(j["rows"][1]["status"], "failed");
  EXPECT_NE(j["rows"][1]["error"].get<std::string>().find("fake failure"), std::string::npos) << j["rows"][1];
  EXPECT_EQ(j["rows"][2]["status"], "failed");
  EXPECT_EQ(j["rows"][3]["status"], "ok");  // the bench went on
  EXPECT_EQ(j["failed_rows"], 2);
  EXPECT_NE(testing::ReadFileBytes(out / "bench.md").find("## Failed rows"), std::string::npos);
}

// `sacfuse simulate --no-pose-errors` (the ablation "without pose errors"): written poses are the true ones, every
// other error is still drawn.
TEST(QualityBenchEndToEndTest, SimulateWithoutPoseErrorsKeepsTheDepthErrors) {
  testing::TempDir dir;
  std::string log;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " simulate --preset tiny --seed 7 --no-pose-errors --no-normal-maps "
                                         "--no-consistency-graphs --out " + ShellQuote(dir / "b"),
                       &log),
            0)
      << log;
  const nlohmann::json m = ReadJsonFile(dir / "b" / "metadata.json");
  EXPECT_TRUE(m["options"]["errors"]["enabled"].get<bool>());
  EXPECT_EQ(m["options"]["errors"]["pose_position_sigma_m"].get<double>(), 0.0);
  EXPECT_EQ(m["options"]["errors"]["pose_rotation_sigma_deg"].get<double>(), 0.0);
  EXPECT_GT(m["options"]["errors"]["disparity_sigma_px"].get<double>(), 0.0);
  uint64_t blunders = 0;
  for (const auto& v : m["views"]) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(v["errors"]["pose_center_delta_m"][k].get<double>(), 0.0) << v["name"];
      EXPECT_EQ(v["true_center"][k].get<double>(), v["written_center"][k].get<double>()) << v["name"];
    }
    blunders += v["errors"]["blunder_count"].get<uint64_t>();
  }
  EXPECT_GT(blunders, 0u) << "depth errors are still drawn";
}

}  // namespace
}  // namespace sacfuse
