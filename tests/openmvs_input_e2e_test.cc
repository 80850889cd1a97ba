// End-to-end: OpenMVS .dmap input. A simulated tiny block (COLMAP workspace) is converted with
// `sacfuse convert --to openmvs`, and `sacfuse run` on the COLMAP config and on the OpenMVS config must give the
// same fused cloud up to rounding (same count, coordinates within a few LAS quanta, same colours and source ids),
// untiled and tiled (30 m tiles: windowed depth reads). A corrupt .dmap fails the run naming the file.
//
// Tiled runs plan their depth windows from the block's height range, which each format takes from what it has
// (COLMAP: the sparse points; OpenMVS: a sample of the depth maps), so the plain COLMAP block plans slightly
// different windows (0.1 % more or fewer points). The tiled comparison therefore gives the COLMAP copy sparse
// points at exactly the OpenMVS block's sampled heights: both runs then plan identical tiles and windows.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/colmap_model.h"
#include "io/las_reader.h"
#include "io/openmvs_block.h"
#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;

class OpenMvsInputEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock();
    WriteConfig("colmap_untiled", "format: colmap, path: " + Block().string(), 0.0);
    std::string out;
    const int code = RunCommand(SacfuseBinary() + " convert " + ShellQuote(Config("colmap_untiled")) +
                                    " --to openmvs --out " + ShellQuote(Converted()),
                                &out);
    ASSERT_EQ(code, 0) << out;
  }
  static fs::path Converted() { return Dir() / "openmvs"; }

  // A config reading `input` (YAML flow mapping body) into Out(name).
  static fs::path WriteConfig(const std::string& name, const std::string& input, double tile_size_m) {
    std::ofstream(Config(name)) << "input: {" << input << "}\n"
                                << "output: {dir: " << Out(name).string() << "}\n"
                                << "tiling: {tile_size_m: " << tile_size_m << ", halo_m: 5}\n";
    return Config(name);
  }

  static void Run(const fs::path& config) {
    std::string out;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &out), 0) << out;
  }
};

// Compares two fused clouds point by point (both runs emit points in the same order) and prints the numbers.
void ExpectSameCloud(const fs::path& a_path, const fs::path& b_path, const std::string& what) {
  LasHeader ha, hb;
  const std::vector<LasPoint> a = ReadAllLasPoints(a_path.string(), &ha);
  const std::vector<LasPoint> b = ReadAllLasPoints(b_path.string(), &hb);
  ASSERT_GT(a.size(), 10000u) << what;
  ASSERT_EQ(a.size(), b.size()) << what;
  const double quantum = ha.scale.x();
  double worst_m = 0.0;
  size_t colour_diffs = 0, source_diffs = 0, moved = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double diff_m = (a[i].xyz - b[i].xyz).cwiseAbs().maxCoeff();
    worst_m = std::max(worst_m, diff_m);
    moved += diff_m > 0.0 ? 1 : 0;
    colour_diffs += a[i].rgb != b[i].rgb ? 1 : 0;
    source_diffs += a[i].point_source_id != b[i].point_source_id ? 1 : 0;
  }
  std::cout << what << ": " << a.size() << " points each; largest coordinate difference " << worst_m / quantum
            << " LAS quanta (" << worst_m * 1000.0 << " mm), " << moved << " points not identical; " << colour_diffs << " colour and " << source_diffs
            << " source-id differences\n";
  EXPECT_LE(worst_m, 3.0 * quantum) << what;
  EXPECT_EQ(colour_diffs, 0u) << what;
  EXPECT_EQ(source_diffs, 0u) << what;
}

TEST_F(OpenMvsInputEndToEndTest, ConvertWritesDmapsImagesAndAConfig) {
  size_t dmaps = 0;
  for (const auto& e : fs::directory_iterator(Converted())) dmaps += e.path().extension() == ".dmap" ? 1 : 0;
  EXPECT_EQ(dmaps, 20u);  // the tiny preset's 20 views
  EXPECT_TRUE(fs::exists(Converted() / "depth0000.dmap"));
  EXPECT_TRUE(fs::exists(Converted() / "depth0019.dmap"));
  EXPECT_TRUE(fs::is_directory(Converted() / "images"));
  std::ifstream yaml(Converted() / "sacfuse.yaml");
  const std::string text((std::istreambuf_iterator<char>(yaml)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("openmvs"), std::string::npos) << text;
  // Converting into a folder that already holds depth maps is refused (stale views).
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " convert " + ShellQuote(Config("colmap_untiled")) +
                           " --to openmvs --out " + ShellQuote(Converted()),
                       &out),
            1)
      << out;
  EXPECT_NE(out.find("already holds OpenMVS depth maps"), std::string::npos) << out;
}

TEST_F(OpenMvsInputEndToEndTest, UntiledRunGivesTheColmapCloud) {
  Run(Config("colmap_untiled"));
  Run(Converted() / "sacfuse.yaml");  // the config convert wrote: output in <converted>/out
  ExpectSameCloud(Out("colmap_untiled") / "fused.laz", Converted() / "out" / "fused.laz", "untiled");
}

TEST_F(OpenMvsInputEndToEndTest, TiledRunGivesTheColmapCloud) {
  // The COLMAP block with sparse points at the OpenMVS block's planning heights (see the top of this file).
  const fs::path colmap = Dir() / "colmap_same_heights";
  fs::copy(Block(), colmap, fs::copy_options::recursive);
  ColmapModel model = ReadColmapModel((colmap / "sparse").string());
  for (ColmapImage& image : model.images) {
    for (ColmapPoint2D& p : image.points2D) p.point3D_id = UINT64_MAX;
  }
  model.points3D.clear();
  for (const double z : OpenMvsBlock(Converted().string()).SceneHeights()) {
    ColmapPoint3D p;
    p.point3D_id = model.points3D.size() + 1;
    p.xyz.z() = z;
    model.points3D.emplace(p.point3D_id, p);
  }
  WriteColmapModelBinary(model, (colmap / "sparse").string());

  Run(WriteConfig("colmap_tiled", "format: colmap, path: " + colmap.string(), 30.0));
  Run(WriteConfig("openmvs_tiled", "format: openmvs, path: " + Converted().string(), 30.0));
  const nlohmann::json plan_a = testing::ReadJsonFile(Out("colmap_tiled") / "plan.json");
  const nlohmann::json plan_b = testing::ReadJsonFile(Out("openmvs_tiled") / "plan.json");
  EXPECT_EQ(plan_a.at("z_range_m"), plan_b.at("z_range_m"));
  ASSERT_EQ(plan_a.at("tiles").size(), plan_b.at("tiles").size());
  ASSERT_GT(plan_a.at("tiles").size(), 4u);
  for (size_t t = 0; t < plan_a.at("tiles").size(); ++t) {
    const auto& va = plan_a.at("tiles")[t].at("views");
    const auto& vb = plan_b.at("tiles")[t].at("views");
    ASSERT_EQ(va.size(), vb.size()) << "tile " << t;
    for (size_t v = 0; v < va.size(); ++v) EXPECT_EQ(va[v].at("window"), vb[v].at("window")) << "tile " << t;
  }
  ExpectSameCloud(Out("colmap_tiled") / "fused.laz", Out("openmvs_tiled") / "fused.laz", "tiled (30 m)");
}

TEST_F(OpenMvsInputEndToEndTest, CorruptDmapFailsTheRunNamingTheFile) {
  const fs::path copy = Dir() / "openmvs_corrupt";
  fs::copy(Converted(), copy, fs::copy_options::recursive);
  fs::remove_all(copy / "out");
  const fs::path bad = copy / "depth0003.dmap";
  fs::resize_file(bad, fs::file_size(bad) - 100);
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " run " +
                           ShellQuote(WriteConfig("corrupt", "format: openmvs, path: " + copy.string(), 0.0)),
                       &out),
            1)
      << out;
  EXPECT_NE(out.find(bad.string() + ": truncated depth map"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(Out("corrupt") / "fused.laz"));
}

}  // namespace
}  // namespace sacfuse
