#include "tools/sim/consistency_graphs.h"

#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/colmap_array.h"
#include "io/colmap_consistency_graph.h"
#include "io/colmap_workspace.h"
#include "tests/support/test_support.h"
#include "tools/sim/sim_workspace.h"
#include "tools/sim/simulate.h"

namespace sacfuse::sim {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const fs::path& p) { return testing::ReadFileBytes(p); }

// Nadir camera over a plane: camera x = world x, camera y = world -y, z down. 160 x 120 px, f = 400 px, 100 m
// above the ground: GSD 0.25 m, depth tolerance max(1 m, 0.5 m) = 1 m.
constexpr int kWidth = 160, kHeight = 120;
constexpr double kFocal = 400.0, kGroundZ = 100.0, kFlyingHeight = 100.0;
constexpr double kX0 = 390000.0, kY0 = 5705000.0;  // UTM-sized coordinates, as the simulator writes them

View NadirView(uint32_t index, const std::string& name, double center_x) {
  View v;
  v.index = index;
  v.name = name;
  v.camera = {kWidth, kHeight, kFocal, kFocal, kWidth / 2.0, kHeight / 2.0};
  v.cam_from_world.rotation = Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);  // 180 degrees about x
  v.cam_from_world.translation =
      -(v.cam_from_world.rotation * Eigen::Vector3d(center_x, kY0, kGroundZ + kFlyingHeight));
  return v;
}

// Two nadir views 10 m apart along x (= 40 px): view 0's column c sees the ground of view 1's column c - 40.
// view 1's depth map is biased by `bias_m`. Returns the graphs written, as read back.
std::vector<ConsistencyGraph> TwoNadirViews(double bias_m, const fs::path& dir) {
  const std::vector<View> views = {NadirView(0, "nadir/a.jpg", kX0), NadirView(1, "nadir/b.jpg", kX0 + 10.0)};
  for (const View& v : views) {
    const std::string path = (dir / "stereo/depth_maps" / (v.name + ".geometric.bin")).string();
    CreateParentDirs(path);
    WriteColmapArray(path, DepthMap(kWidth, kHeight, 1, static_cast<float>(kFlyingHeight + (v.index ? bias_m : 0))));
  }
  size_t last_done = 0, last_total = 0;
  const ConsistencyGraphSummary s = WriteConsistencyGraphs(dir.string(), views, {}, [&](size_t done, size_t total) {
    last_done = done;
    last_total = total;
  });
  EXPECT_EQ(s.num_graphs, 2u);
  EXPECT_EQ(last_done, 2u);
  EXPECT_EQ(last_total, 2u);
  std::vector<ConsistencyGraph> graphs;
  for (const View& v : views) {
    graphs.push_back(ReadColmapConsistencyGraph((dir / "stereo/consistency_graphs" / (v.name + ".geometric.bin")).string()));
  }
  return graphs;
}

// Pixels whose list is not exactly `expected`.
int CountMismatches(const ConsistencyGraph& g, const std::function<std::vector<uint32_t>(int col)>& expected) {
  int bad = 0;
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      const auto [first, last] = g.At(row, col);
      if (std::vector<uint32_t>(first, last) != expected(col)) ++bad;
    }
  }
  return bad;
}

std::vector<uint32_t> OverlapOnly(bool overlap, uint32_t other) {
  return overlap ? std::vector<uint32_t>{other} : std::vector<uint32_t>{};
}

TEST(ConsistencyGraphsTest, FlatPlaneOverlapListsTheOtherViewOnly) {
  testing::TempDir dir;
  const auto graphs = TwoNadirViews(0.0, dir.path());
  ASSERT_EQ(graphs.size(), 2u);
  ASSERT_EQ(graphs[0].width, kWidth);
  ASSERT_EQ(graphs[0].height, kHeight);
  // view 0: columns >= 40 are inside view 1; view 1: columns < 120 are inside view 0.
  EXPECT_EQ(CountMismatches(graphs[0], [](int col) { return OverlapOnly(col >= 40, 1); }), 0);
  EXPECT_EQ(CountMismatches(graphs[1], [](int col) { return OverlapOnly(col < kWidth - 40, 0); }), 0);
  EXPECT_EQ(graphs[0].view_indices.size(), static_cast<size_t>(kWidth - 40) * kHeight);
}

TEST(ConsistencyGraphsTest, DepthBiasBeyondToleranceIsInconsistent) {
  const auto nothing = [](int) { return std::vector<uint32_t>{}; };
  for (const double bias : {10.0, 1.5, -1.5}) {  // 10 m: boxes apart; 1.5 m: boxes meet, the depth check rejects
    testing::TempDir dir;
    const auto graphs = TwoNadirViews(bias, dir.path());
    EXPECT_EQ(CountMismatches(graphs[0], nothing), 0) << "bias " << bias;
    EXPECT_EQ(CountMismatches(graphs[1], nothing), 0) << "bias " << bias;
  }
  testing::TempDir dir;  // within the 1 m tolerance: still consistent
  const auto graphs = TwoNadirViews(0.7, dir.path());
  EXPECT_EQ(CountMismatches(graphs[0], [](int col) { return OverlapOnly(col >= 40, 1); }), 0);
}

TEST(ConsistencyGraphsTest, ComputeHonoursPixelCapAndInvalidDepth) {
  const View a = NadirView(0, "a", kX0), b = NadirView(1, "b", kX0 + 10.0);
  DepthMap da(kWidth, kHeight, 1, kFlyingHeight), db(kWidth, kHeight, 1, kFlyingHeight);
  for (int row = 0; row < kHeight; ++row) db.at(row, 0) = 0.0f;  // view 0's column 40 lands here
  std::vector<DepthViewRef> views = {{&da, a.camera, a.cam_from_world}, {&db, b.camera, b.cam_from_world}};
  const ConsistencyGraph g = ComputeConsistencyGraph(0, views, {1}, {});
  EXPECT_EQ(CountMismatches(g, [](int col) { return OverlapOnly(col >= 41, 1); }), 0);
  ConsistencyGraphOptions capped;
  capped.max_views_per_pixel = 0;
  EXPECT_TRUE(ComputeConsistencyGraph(0, views, {1}, capped).view_indices.empty());
}

// One tiny preset block for the end-to-end checks.
class TinyConsistencyTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir();
    stages_ = new std::set<std::string>();
    summary_ = new SimSummary(SimulateBlock(SimPreset("tiny"), dir_->path().string(),
                                            [](const std::string& stage, size_t, size_t) { stages_->insert(stage); }));
  }
  static void TearDownTestSuite() {
    delete summary_;
    delete stages_;
    delete dir_;
  }
  static fs::path Out() { return dir_->path(); }
  static std::map<std::string, std::string> GraphBytes(const ColmapWorkspace& ws) {
    std::map<std::string, std::string> bytes;
    for (const View& v : ws.views()) bytes[v.name] = ReadBytes(ws.ConsistencyGraphPath(v));
    return bytes;
  }

  static testing::TempDir* dir_;
  static std::set<std::string>* stages_;
  static SimSummary* summary_;
};
testing::TempDir* TinyConsistencyTest::dir_ = nullptr;
std::set<std::string>* TinyConsistencyTest::stages_ = nullptr;
SimSummary* TinyConsistencyTest::summary_ = nullptr;

TEST_F(TinyConsistencyTest, OneReadableGraphPerImageWithIndicesInRange) {
  EXPECT_TRUE(SimPreset("tiny").write_consistency_graphs);
  EXPECT_TRUE(stages_->count("consistency"));
  const ColmapWorkspace ws(Out().string(), ColmapDepthType::kGeometric);
  ASSERT_EQ(ws.views().size(), static_cast<size_t>(summary_->num_views));
  EXPECT_EQ(summary_->consistency_graphs, summary_->num_views);
  const size_t n = ws.model().images.size();
  for (const View& v : ws.views()) {
    ASSERT_TRUE(ws.HasConsistencyGraph(v)) << v.name;
    const ConsistencyGraph raw = ReadColmapConsistencyGraph(ws.ConsistencyGraphPath(v));
    const ColmapArrayShape shape = ReadColmapArrayShape(ws.DepthMapPath(v));
    EXPECT_EQ(raw.width, shape.width) << v.name;
    EXPECT_EQ(raw.height, shape.height) << v.name;
    EXPECT_FALSE(raw.view_indices.empty()) << v.name;
    // images.bin order == view order in the simulator, so the own index is v.index.
    EXPECT_EQ(ws.model().images[v.index].name, v.name);
    for (size_t p = 0; p + 1 < raw.pixel_offsets.size(); ++p) {
      ASSERT_LE(raw.pixel_offsets[p + 1] - raw.pixel_offsets[p], 20u) << v.name;
      for (uint32_t k = raw.pixel_offsets[p]; k < raw.pixel_offsets[p + 1]; ++k) {
        ASSERT_LT(raw.view_indices[k], n) << v.name;
        ASSERT_NE(raw.view_indices[k], v.index) << v.name;
        if (k > raw.pixel_offsets[p]) {
          ASSERT_LT(raw.view_indices[k - 1], raw.view_indices[k]) << v.name;
        }
      }
    }
  }
  const nlohmann::json meta = nlohmann::json::parse(ReadBytes(Out() / "metadata.json"));
  EXPECT_TRUE(meta["options"]["write_consistency_graphs"].get<bool>());
  EXPECT_EQ(meta["files"]["consistency_graphs"], "stereo/consistency_graphs");
  EXPECT_EQ(meta["consistency_graphs"]["graphs"].get<int>(), summary_->num_views);
}

TEST_F(TinyConsistencyTest, MostValidNadirPixelsListAView) {
  const ColmapWorkspace ws(Out().string(), ColmapDepthType::kGeometric);
  int nadir = 0;
  for (const View& v : ws.views()) {
    if (v.name.find("nadir") == std::string::npos) continue;
    ++nadir;
    const DepthMap depth = ws.ReadDepthMap(v);
    const ConsistencyGraph g = ws.ReadConsistencyGraph(v);
    ASSERT_EQ(g.width, depth.width);
    ASSERT_EQ(g.height, depth.height);
    size_t valid = 0, listed = 0, listed_invalid = 0;
    for (int row = 0; row < depth.height; ++row) {
      for (int col = 0; col < depth.width; ++col) {
        const auto [first, last] = g.At(row, col);
        const bool any = first != last;
        if (IsValidDepth(depth.at(row, col))) {
          ++valid;
          listed += any;
        } else {
          listed_invalid += any;
        }
      }
    }
    ASSERT_GT(valid, 0u) << v.name;
    EXPECT_GT(static_cast<double>(listed) / valid, 0.8) << v.name << ": " << listed << " of " << valid;
    EXPECT_EQ(listed_invalid, 0u) << v.name;
  }
  EXPECT_GT(nadir, 0);
}

TEST_F(TinyConsistencyTest, SameBytesForOneAndTwoThreads) {
  const ColmapWorkspace ws(Out().string(), ColmapDepthType::kGeometric);
  const auto from_simulate = GraphBytes(ws);
  ConsistencyGraphOptions o;
  o.num_threads = 1;
  WriteConsistencyGraphs(Out().string(), ws.views(), o);
  const auto one = GraphBytes(ws);
  o.num_threads = 2;
  WriteConsistencyGraphs(Out().string(), ws.views(), o);
  const auto two = GraphBytes(ws);
  ASSERT_EQ(one.size(), ws.views().size());
  for (const auto& [name, bytes] : one) {
    EXPECT_GT(bytes.size(), 20u) << name;
    EXPECT_TRUE(bytes == two.at(name)) << name;
    EXPECT_TRUE(bytes == from_simulate.at(name)) << name;
  }
}

TEST(ConsistencyGraphsOptionTest, OffWritesNoGraphs) {
  SimOptions o = SimPreset("tiny");
  o.write_consistency_graphs = false;
  o.obliques = false;
  o.max_nadir_views = 2;
  testing::TempDir dir;
  const SimSummary s = SimulateBlock(o, dir.path().string());
  EXPECT_EQ(s.consistency_graphs, 0);
  EXPECT_FALSE(fs::exists(dir / "stereo/consistency_graphs"));
  EXPECT_TRUE(fs::exists(dir / "stereo/depth_maps"));
  EXPECT_FALSE(SimPreset("medium").write_consistency_graphs);
  EXPECT_FALSE(SimPreset("dortmund").write_consistency_graphs);
  EXPECT_FALSE(SimPreset("small").write_consistency_graphs);
  EXPECT_TRUE(SimPreset("tiny").write_consistency_graphs);
}

}  // namespace
}  // namespace sacfuse::sim
