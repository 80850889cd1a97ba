// End-to-end: the tiled job system on a simulated tiny block. `sacfuse plan` lists every tile and writes
// plan.json; a tiled SAC run (20 m tiles, 5 m halo) stitches without duplicates, every point lies in exactly one
// tile core, and the tiled cloud agrees with the untiled one (point count within 3 %, F1 within 1 point).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <tuple>
#include <vector>

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

nlohmann::json ReadJson(const fs::path& path) { return testing::ReadJsonFile(path); }
double F1(const fs::path& eval_json, size_t threshold) { return testing::EvalF1(eval_json, threshold); }

class TilingEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock();
    const double gsd = BlockGsd();
    // tile_size_m 0 with the default 4 GB budget: the tiny block fits, so it runs untiled. "auto_t1"/"auto_t2":
    // a 0.145 GiB budget the whole block does not fit (~0.1465 GiB estimated; 128 MiB of it the process base), so
    // tiles are sized from it, run on one and on two threads. "guard": 60 m tiles given explicitly, which exceed a
    // 0.14 GiB budget.
    struct Variant {
      std::string name;
      double tile_size_m;
      std::string resources;
    };
    for (const Variant& v : {Variant{"untiled", 0.0, ""}, Variant{"tiled", 20.0, ""},
                             Variant{"auto_t1", 0.0, "resources: {memory_gb: 0.145, threads: 1}\n"},
                             Variant{"auto_t2", 0.0, "resources: {memory_gb: 0.145, threads: 2}\n"},
                             Variant{"guard", 60.0, "resources: {memory_gb: 0.14}\n"}}) {
      const std::string& name = v.name;
      std::ofstream(Config(name)) << "input: {path: " << Block().string() << "}\n"
                                  << "output: {dir: " << Out(name).string() << "}\n"
                                  << "tiling: {tile_size_m: " << v.tile_size_m << ", halo_m: 5}\n"
                                  << v.resources
                                  << "evaluation: {reference: " << (Block() / "reference.las").string()
                                  << ", mask: " << (Block() / "eval_mask.png").string() << ", gsd_m: " << gsd
                                  << "}\n";
    }
  }
};

TEST_F(TilingEndToEndTest, PlanPrintsEveryTileAndWritesViewsAndWindows) {
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " plan " + ShellQuote(Config("tiled")), &out), 0) << out;
  const nlohmann::json plan = ReadJson(Out("tiled") / "plan.json");
  ASSERT_GT(plan.at("tiles").size(), 4u);
  EXPECT_EQ(plan.at("tile_size_m").get<double>(), 20.0);
  size_t tiles_with_views = 0;
  for (const auto& tile : plan.at("tiles")) {
    const std::string id = tile.at("id").get<std::string>();
    EXPECT_NE(out.find("\n" + id + " "), std::string::npos) << "tile " << id << " missing from:\n" << out;
    for (const auto& v : tile.at("views")) {
      const auto& w = v.at("window");
      EXPECT_LT(w.at("row_begin").get<int>(), w.at("row_end").get<int>());
      EXPECT_LT(w.at("col_begin").get<int>(), w.at("col_end").get<int>());
      EXPECT_FALSE(v.at("name").get<std::string>().empty());
    }
    tiles_with_views += tile.at("views").empty() ? 0 : 1;
  }
  EXPECT_GT(tiles_with_views, 4u);
  EXPECT_EQ(RunCommand(SacfuseBinary() + " plan " + ShellQuote(Dir() / "missing.yaml"), &out), 2) << out;
}

TEST_F(TilingEndToEndTest, TiledRunStitchesWithoutSeamsAndMatchesUntiled) {
  std::string out;
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("untiled")), &out), 0) << out;
  const auto t1 = std::chrono::steady_clock::now();
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("tiled")), &out), 0) << out;
  const auto t2 = std::chrono::steady_clock::now();
  ASSERT_EQ(RunCommand(SacfuseBinary() + " plan " + ShellQuote(Config("tiled")), &out), 0) << out;
  const nlohmann::json plan = ReadJson(Out("tiled") / "plan.json");
  EXPECT_GT(ReadJson(Out("tiled") / "run_report.json").at("tiling").at("tiles_run").get<int>(), 4);

  const std::vector<LasPoint> tiled = ReadAllLasPoints((Out("tiled") / "fused.laz").string());
  const uint64_t untiled_count = LasReader((Out("untiled") / "fused.laz").string()).header().point_count;
  ASSERT_GT(tiled.size(), 1000u);

  // (b) Every XY in exactly one half-open tile core; (a) no duplicates (quantised XYZ + source ID), counting
  // how many points lie within 1 m of a core border so the check is known to cover the seams.
  std::vector<std::array<double, 4>> cores;
  for (const auto& tile : plan.at("tiles")) cores.push_back(tile.at("core").get<std::array<double, 4>>());
  std::vector<std::tuple<int64_t, int64_t, int64_t, uint16_t>> keys;
  keys.reserve(tiled.size());
  size_t outside = 0, multiple = 0, near_border = 0;
  for (const LasPoint& p : tiled) {
    int inside = 0;
    for (const auto& c : cores) {
      if (p.xyz.x() >= c[0] && p.xyz.x() < c[2] && p.xyz.y() >= c[1] && p.xyz.y() < c[3]) {
        ++inside;
        const double d = std::min({p.xyz.x() - c[0], c[2] - p.xyz.x(), p.xyz.y() - c[1], c[3] - p.xyz.y()});
        near_border += d < 1.0 ? 1 : 0;
      }
    }
    outside += inside == 0 ? 1 : 0;
    multiple += inside > 1 ? 1 : 0;
    keys.emplace_back(std::llround(p.xyz.x() * 1000), std::llround(p.xyz.y() * 1000), std::llround(p.xyz.z() * 1000),
                      p.point_source_id);
  }
  EXPECT_EQ(outside, 0u);
  EXPECT_EQ(multiple, 0u);
  EXPECT_GT(near_border, 1000u);
  std::sort(keys.begin(), keys.end());
  const size_t duplicates = keys.size() - (std::unique(keys.begin(), keys.end()) - keys.begin());
  EXPECT_EQ(duplicates, 0u);

  // (c) Agreement with the untiled run.
  const double ratio = static_cast<double>(tiled.size()) / static_cast<double>(untiled_count);
  EXPECT_NEAR(ratio, 1.0, 0.03) << tiled.size() << " tiled vs " << untiled_count << " untiled points";
  std::vector<double> f1_untiled, f1_tiled;
  for (size_t t = 0; t < 2; ++t) {
    f1_untiled.push_back(F1(Out("untiled") / "eval.json", t));
    f1_tiled.push_back(F1(Out("tiled") / "eval.json", t));
    EXPECT_NEAR(f1_tiled[t], f1_untiled[t], 0.01) << "threshold " << t;  // F1 as a fraction: 1 point = 0.01
  }
  std::printf("tiling e2e: untiled %llu points, F1 %.4f / %.4f, %.1f s; tiled %zu points (%+.2f %%), F1 %.4f / "
              "%.4f, %.1f s; %zu points within 1 m of a core border, %zu duplicates\n",
              static_cast<unsigned long long>(untiled_count), f1_untiled[0], f1_untiled[1],
              std::chrono::duration<double>(t1 - t0).count(), tiled.size(), 100.0 * (ratio - 1.0), f1_tiled[0],
              f1_tiled[1], std::chrono::duration<double>(t2 - t1).count(), near_border, duplicates);
}

TEST_F(TilingEndToEndTest, BudgetSizesTilesAndThreadsDoNotChangeTheOutput) {
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("auto_t1")), &out), 0) << out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("auto_t2")), &out), 0) << out;
  EXPECT_NE(out.find("2 worker threads"), std::string::npos) << out;
  for (const std::string name : {"auto_t1", "auto_t2"}) {
    const nlohmann::json report = ReadJson(Out(name) / "run_report.json");
    const double tile = report.at("tiling_decision").at("tile_size_m").get<double>();
    EXPECT_GT(tile, 0.0) << name << ": the block should not fit the budget untiled";
    EXPECT_GT(report.at("tiling").at("tiles_run").get<int>(), 1);
    EXPECT_LE(report.at("memory").at("estimate_gib").get<double>(), 0.145);
    // The whole process stayed inside the budget (0.145 GiB = 148.5 MiB); not measurable under a sanitizer.
    if (!testing::kSanitizedBuild) EXPECT_LT(report.at("peak_rss_mib").get<double>(), 0.145 * 1024) << name;
  }
  // One or two tile workers: the same tiles, the same bytes (but for the header's creation date).
  EXPECT_EQ(testing::WithoutLasCreationDate(testing::ReadFileBytes(Out("auto_t1") / "fused.laz")),
            testing::WithoutLasCreationDate(testing::ReadFileBytes(Out("auto_t2") / "fused.laz")));
}

TEST_F(TilingEndToEndTest, TilesOverTheBudgetFailWithTheOutOfMemoryGuard) {
  std::string out;
  const int code = RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("guard")), &out);
  EXPECT_NE(code, 0) << out;
  EXPECT_NE(out.find("out-of-memory guard"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(Out("guard") / "fused.laz"));
  // The last run failed: status says so and exits 1 (jobs/run_state.h); no run ever completed, so no cloud.
  ASSERT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config("guard")), &out), 1) << out;
  EXPECT_NE(out.find("out-of-memory guard"), std::string::npos) << out;
  EXPECT_NE(out.find("last run FAILED at "), std::string::npos) << out;
  EXPECT_NE(out.find("no fused.laz: no run has completed"), std::string::npos) << out;
}

}  // namespace
}  // namespace sacfuse
