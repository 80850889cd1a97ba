// Which aerial-bench blocks `sacfuse bench` makes: the six definitions of docs/evaluation.md, LiDAR
// files expanded, and blocks skipped with a reason when the aerial-bench folder or a LiDAR file is missing.
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/test_support.h"
#include "tools/bench/aerial_bench_plan.h"

namespace sacfuse::bench {
namespace {

namespace fs = std::filesystem;

void Touch(const fs::path& p) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "x";
}

// A fake aerial-bench folder and LiDAR folder with the files the definitions need.
QualityBenchOptions Options(const testing::TempDir& dir) {
  Touch(dir / "ab/make_block.py");
  Touch(dir / "lidar/ign_montpellier/test_data_2.las");
  Touch(dir / "lidar/ign_montpellier/test_data_1.las");
  Touch(dir / "lidar/ign_montpellier/other.las");
  Touch(dir / "lidar/lastools/zurich.las");
  Touch(dir / "lidar/ign_tiles/St_Barth_RGAF09_UTM20N_IGN_1988_SB_subset_100m.laz");
  QualityBenchOptions o;
  o.aerial_bench_dir = (dir / "ab").string();
  o.lidar_dir = (dir / "lidar").string();
  o.python = "/bin/sh";  // any executable: the plan only checks it exists
  return o;
}

TEST(AerialBenchPlanTest, DefaultBlocksAreTheSixDefinitions) {
  testing::TempDir dir;
  const AerialPlan plan = BuildAerialPlan(Options(dir));
  EXPECT_TRUE(plan.skipped.empty());
  ASSERT_EQ(plan.blocks.size(), 6u);
  const std::string m1 = (dir / "lidar/ign_montpellier/test_data_1.las").string();
  const std::string m2 = (dir / "lidar/ign_montpellier/test_data_2.las").string();
  const std::string z = (dir / "lidar/lastools/zurich.las").string();
  EXPECT_EQ(plan.blocks[0].name, "montpellier");
  EXPECT_EQ(plan.blocks[0].make_args, (std::vector<std::string>{m1, m2, "--gsd", "0.25"}));
  EXPECT_EQ(plan.blocks[1].make_args, (std::vector<std::string>{m1, m2, "--gsd", "0.25", "--error-scale", "2.5"}));
  EXPECT_EQ(plan.blocks[2].make_args, (std::vector<std::string>{z, "--gsd", "0.125", "--cell", "0.25"}));
  EXPECT_EQ(plan.blocks[3].make_args,
            (std::vector<std::string>{z, "--gsd", "0.125", "--cell", "0.25", "--error-scale", "2.5"}));
  for (size_t i = 0; i < 4; ++i) EXPECT_TRUE(plan.blocks[i].laz_inputs.empty()) << plan.blocks[i].name;
  // The third city is shared as LAZ only: listed for decoding before make_block.py.
  const std::string sb = (dir / "lidar/ign_tiles/St_Barth_RGAF09_UTM20N_IGN_1988_SB_subset_100m.laz").string();
  EXPECT_EQ(plan.blocks[4].name, "stbarth");
  EXPECT_EQ(plan.blocks[4].make_args, (std::vector<std::string>{sb, "--gsd", "0.125", "--cell", "0.25"}));
  EXPECT_EQ(plan.blocks[4].laz_inputs, (std::vector<std::string>{sb}));
  EXPECT_EQ(plan.blocks[5].name, "stbarth_e25");
  EXPECT_EQ(plan.blocks[5].make_args.back(), "2.5");
  EXPECT_EQ(plan.python, "/bin/sh");
}

TEST(AerialBenchPlanTest, MissingFolderSkipsEveryBlockWithAMessage) {
  testing::TempDir dir;
  QualityBenchOptions o = Options(dir);
  o.aerial_bench_dir = (dir / "nowhere").string();
  o.aerial_blocks = {"zurich", "montpellier_e25"};
  AerialPlan plan = BuildAerialPlan(o);
  EXPECT_TRUE(plan.blocks.empty());
  ASSERT_EQ(plan.skipped.size(), 2u);
  EXPECT_EQ(plan.skipped[0].scene, "aerial zurich");
  EXPECT_EQ(plan.skipped[1].scene, "aerial montpellier_e25");
  EXPECT_EQ(plan.skipped[0].reason,
            "aerial-bench not found: " + (dir / "nowhere" / "make_block.py").string() + " is missing");
  o.aerial_bench_dir.clear();  // auto found nothing
  plan = BuildAerialPlan(o);
  ASSERT_EQ(plan.skipped.size(), 2u);
  EXPECT_NE(plan.skipped[0].reason.find("aerial-bench not found"), std::string::npos);
}

TEST(AerialBenchPlanTest, MissingLidarFileSkipsOnlyItsBlocks) {
  testing::TempDir dir;
  QualityBenchOptions o = Options(dir);
  fs::remove(dir / "lidar/lastools/zurich.las");
  const AerialPlan plan = BuildAerialPlan(o);
  ASSERT_EQ(plan.blocks.size(), 4u);
  EXPECT_EQ(plan.blocks[1].name, "montpellier_e25");
  EXPECT_EQ(plan.blocks[2].name, "stbarth");
  ASSERT_EQ(plan.skipped.size(), 2u);
  EXPECT_EQ(plan.skipped[0].reason, "LiDAR file not found: " + (dir / "lidar/lastools/zurich.las").string());
}

TEST(AerialBenchPlanTest, OffAndUnknownNames) {
  testing::TempDir dir;
  QualityBenchOptions o = Options(dir);
  o.aerial_blocks.clear();
  const AerialPlan plan = BuildAerialPlan(o);
  EXPECT_TRUE(plan.blocks.empty());
  EXPECT_TRUE(plan.skipped.empty());
  o.aerial_blocks = {"dortmund"};
  EXPECT_NE(testing::ErrorOf<ConfigError>([&] { BuildAerialPlan(o); }).find("--aerial-blocks: unknown block 'dortmund'"),
            std::string::npos);
  QualityBenchOptions quick;
  ApplyQuickPreset(&quick);
  EXPECT_TRUE(quick.aerial_blocks.empty());
}

}  // namespace
}  // namespace sacfuse::bench
