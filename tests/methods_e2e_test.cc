// End-to-end: the paper's comparison methods (fusion.method union | consistency | disparity_normal | tsdf |
// multiray) on a simulated tiny block, each untiled and in 20 m tiles with a 5 m halo, through the same inputs,
// tiles and LAS outputs as SAC: every run writes a valid LAS with source ids and is scored; tiled and untiled
// agree (point counts, F1, density along tile borders: no doubled points); `tile` workers + `merge` give the
// cloud of `run`; methods without superpixels compute none; and the orderings that hold by construction hold (the union is the least accurate, the averaging and
// filtering methods keep fewer points than the union).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
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
using testing::SacfuseBinary;
using testing::ShellQuote;

const std::vector<std::string> kMethods = {"union", "consistency", "disparity_normal", "tsdf", "multiray"};
constexpr double kTileM = 20.0;

struct RunResult {
  int exit_code = -1;
  std::string output;
};

class MethodsEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock();
    results_ = new std::map<std::string, RunResult>();
    for (const std::string& method : kMethods) {
      for (const bool tiled : {false, true}) {
        const std::string name = Name(method, tiled);
        std::ofstream(Config(name)) << "input: {path: " << Block().string() << "}\n"
                                    << "output: {dir: " << Out(name).string() << "}\n"
                                    << "fusion: {method: " << method << "}\n"
                                    << "tiling: {tile_size_m: " << (tiled ? kTileM : 0.0) << ", halo_m: 5}\n"
                                    << "evaluation: {reference: " << (Block() / "reference.las").string()
                                    << ", mask: " << (Block() / "eval_mask.png").string() << ", gsd_m: " << BlockGsd()
                                    << "}\n";
        RunResult r;
        r.exit_code = RunCommand(SacfuseBinary() + " run " + ShellQuote(Config(name)), &r.output);
        (*results_)[name] = r;
      }
    }
  }
  static void TearDownTestSuite() {
    delete results_;
    results_ = nullptr;
    testing::TinyBlockSuite::TearDownTestSuite();
  }
  static std::string Name(const std::string& method, bool tiled) { return method + (tiled ? "_tiled" : "_untiled"); }
  static const RunResult& Result(const std::string& name) { return results_->at(name); }
  static nlohmann::json Eval(const std::string& name) { return testing::ReadJsonFile(Out(name) / "eval.json"); }
  static double Score(const std::string& name, const char* what, size_t threshold) {
    return Eval(name).at("scores").at(threshold).at(what).get<double>();
  }
  static size_t NumViews() {
    return testing::ReadJsonFile(Out(Name("union", false)) / "run_report.json").at("views").size();
  }

 private:
  static inline std::map<std::string, RunResult>* results_ = nullptr;
};

TEST_F(MethodsEndToEndTest, EveryMethodWritesAValidScoredLasWithSourceIdsUntiledAndTiled) {
  const size_t views = NumViews();
  ASSERT_GT(views, 10u);
  for (const std::string& method : kMethods) {
    for (const bool tiled : {false, true}) {
      const std::string name = Name(method, tiled);
      const RunResult& r = Result(name);
      ASSERT_EQ(r.exit_code, 0) << name << ":\n" << r.output;
      LasHeader header;
      const std::vector<LasPoint> points = ReadAllLasPoints((Out(name) / "fused.laz").string(), &header);
      EXPECT_GT(points.size(), 5000u) << name;
      EXPECT_EQ(points.size(), header.point_count) << name;
      std::vector<size_t> per_source(views + 1, 0);
      for (const LasPoint& p : points) {
        ASSERT_GE(p.point_source_id, 1) << name;
        ASSERT_LE(p.point_source_id, views) << name;
        ++per_source[p.point_source_id];
      }
      EXPECT_GT(std::count_if(per_source.begin(), per_source.end(), [](size_t n) { return n > 0; }), 3) << name;
      for (size_t t = 0; t < 2; ++t) {
        for (const char* what : {"accuracy", "completeness", "f1"}) {
          const double v = Score(name, what, t);
          EXPECT_TRUE(std::isfinite(v) && v > 0.0 && v <= 1.0) << name << " " << what << " = " << v;
        }
      }
      const nlohmann::json report = testing::ReadJsonFile(Out(name) / "run_report.json");
      EXPECT_EQ(report.at("method").get<std::string>(), method);
      EXPECT_EQ(report.at("output_points").get<uint64_t>(), points.size()) << name;
      // Points per view as the file holds them (tiled: summed from the tiles' done markers by the merge).
      const nlohmann::json& report_views = report.at("views");
      ASSERT_EQ(report_views.size(), views) << name;
      for (size_t i = 0; i < views; ++i) {
        EXPECT_EQ(report_views[i].at("output_points").get<uint64_t>(), per_source[i + 1]) << name << " view " << i;
      }
      if (tiled) {
        EXPECT_GT(report.at("tiling").at("tiles_run").get<int>(), 4) << name;
      }
      if (method != "union" || tiled) {
        EXPECT_EQ(report.at("fusion").at("points_emitted").get<uint64_t>() >= points.size(), true) << name;
        EXPECT_GT(report.at("input_points").get<uint64_t>(), points.size() / 2) << name;
      }
    }
  }
}

// Counts points within 1 m of an inner tile-core border (x or y close to a multiple of the tile size, the grid
// being aligned to multiples of it).
size_t PointsNearTileBorders(const std::vector<LasPoint>& points) {
  size_t n = 0;
  for (const LasPoint& p : points) {
    const double dx = std::abs(p.xyz.x() - kTileM * std::round(p.xyz.x() / kTileM));
    const double dy = std::abs(p.xyz.y() - kTileM * std::round(p.xyz.y() / kTileM));
    n += std::min(dx, dy) < 1.0 ? 1 : 0;
  }
  return n;
}

TEST_F(MethodsEndToEndTest, TiledAgreesWithUntiledWithoutDuplicatesAlongTileBorders) {
  for (const std::string& method : kMethods) {
    const std::string u = Name(method, false), t = Name(method, true);
    ASSERT_EQ(Result(u).exit_code, 0) << Result(u).output;
    ASSERT_EQ(Result(t).exit_code, 0) << Result(t).output;
    const std::vector<LasPoint> untiled = ReadAllLasPoints((Out(u) / "fused.laz").string());
    const std::vector<LasPoint> tiled = ReadAllLasPoints((Out(t) / "fused.laz").string());
    // No point twice (quantised XYZ + source id).
    std::vector<std::tuple<int64_t, int64_t, int64_t, uint16_t>> keys;
    for (const LasPoint& p : tiled) {
      keys.emplace_back(std::llround(p.xyz.x() * 1000), std::llround(p.xyz.y() * 1000), std::llround(p.xyz.z() * 1000),
                        p.point_source_id);
    }
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(std::unique(keys.begin(), keys.end()), keys.end()) << method << ": duplicated points";
    const double ratio = static_cast<double>(tiled.size()) / static_cast<double>(untiled.size());
    const size_t near_u = PointsNearTileBorders(untiled), near_t = PointsNearTileBorders(tiled);
    const double near_ratio = static_cast<double>(near_t) / static_cast<double>(near_u);
    std::printf("%-17s untiled %8zu points, tiled %8zu (%+.2f %%); within 1 m of tile borders %7zu vs %7zu (%+.2f %%); "
                "F1 2x %.4f vs %.4f\n",
                method.c_str(), untiled.size(), tiled.size(), 100.0 * (ratio - 1.0), near_u, near_t,
                100.0 * (near_ratio - 1.0), Score(u, "f1", 0), Score(t, "f1", 0));
    if (method == "union") {
      EXPECT_EQ(tiled.size(), untiled.size());  // every pixel, each in exactly one tile
    } else {
      EXPECT_NEAR(ratio, 1.0, 0.03) << method;
    }
    EXPECT_GT(near_u, 1000u) << method;                // the border test covers many points
    EXPECT_NEAR(near_ratio, 1.0, 0.05) << method;      // no doubled (or missing) strip along the borders
    for (size_t k = 0; k < 2; ++k) EXPECT_NEAR(Score(t, "f1", k), Score(u, "f1", k), 0.01) << method << " " << k;
  }
}

TEST_F(MethodsEndToEndTest, TileWorkersThenMergeGiveTheCloudOfAPlainRun) {
  // `sacfuse tile` per id (one after another here) and `sacfuse merge` run a comparison method like `run` does
  // (30 m tiles to keep the number of processes small).
  for (const std::string name : {"workers_run", "workers_tiles"}) {
    std::ofstream(Config(name)) << "input: {path: " << Block().string() << "}\n"
                                << "output: {dir: " << Out(name).string() << "}\n"
                                << "fusion: {method: consistency}\n"
                                << "tiling: {tile_size_m: 30, halo_m: 5}\n";
  }
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("workers_run")), &out), 0) << out;
  const std::string list = SacfuseBinary() + " plan --list " + ShellQuote(Config("workers_tiles")) + " 2>/dev/null";
  ASSERT_EQ(RunCommand("for id in $(" + list + "); do " + SacfuseBinary() + " tile " +
                           ShellQuote(Config("workers_tiles")) + " --id $id || exit 1; done",
                       &out),
            0)
      << out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " merge " + ShellQuote(Config("workers_tiles")), &out), 0) << out;
  EXPECT_GT(testing::CountFilesNamedWith(Out("workers_tiles") / "tiles", ".done.json"), 3u);
  EXPECT_EQ(testing::CountFilesNamedWith(Out("workers_tiles"), ".spx"), 0u);
  EXPECT_TRUE(testing::WithoutLasCreationDate(testing::ReadFileBytes(Out("workers_tiles") / "fused.laz")) ==
              testing::WithoutLasCreationDate(testing::ReadFileBytes(Out("workers_run") / "fused.laz")))
      << "tile workers + merge differ from run";
}

TEST_F(MethodsEndToEndTest, MethodsWithoutSuperpixelsComputeNoneButKeepTheColourCache) {
  for (const std::string& method : kMethods) {
    const std::string t = Name(method, true);
    ASSERT_EQ(Result(t).exit_code, 0) << Result(t).output;
    const fs::path cache = Out(t) / "superpixels";
    EXPECT_EQ(testing::CountFilesNamedWith(Out(t), ".spx"), 0u) << method;
    ASSERT_TRUE(fs::exists(cache)) << method;
    EXPECT_EQ(testing::CountFilesNamedWith(cache, ".rgb"), NumViews()) << method;
  }
}

TEST_F(MethodsEndToEndTest, TheUnionIsTheLeastAccurateAndTheFusionsKeepFewerPoints) {
  const std::string u = Name("union", false);
  const uint64_t union_points = LasReader((Out(u) / "fused.laz").string()).header().point_count;
  for (const std::string& method : kMethods) {
    if (method == "union") continue;
    const std::string m = Name(method, false);
    const uint64_t points = LasReader((Out(m) / "fused.laz").string()).header().point_count;
    std::printf("%-17s %9llu points, accuracy %.4f / %.4f, completeness %.4f / %.4f, F1 %.4f / %.4f\n",
                method.c_str(), static_cast<unsigned long long>(points), Score(m, "accuracy", 0),
                Score(m, "accuracy", 1), Score(m, "completeness", 0), Score(m, "completeness", 1), Score(m, "f1", 0),
                Score(m, "f1", 1));
    EXPECT_LT(points, union_points * 3 / 4) << method << " keeps too much of the union";
    EXPECT_GT(Score(m, "accuracy", 0), Score(u, "accuracy", 0)) << method << " is not more accurate than the union";
  }
}

}  // namespace
}  // namespace sacfuse
