// The plan of `sacfuse bench`: which blocks are simulated (with which simulate arguments) and which rows run, for
// the defaults, --quick, COLMAP on, and LiDAR files that are missing (skipped with a reason).
#include <algorithm>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"
#include "tools/bench/quality_bench_plan.h"

namespace sacfuse::bench {
namespace {

std::vector<std::string> Names(const BenchPlan& plan, const std::string& section, double scale = 0) {
  std::vector<std::string> names;
  for (const RowSpec& r : plan.rows) {
    if (r.section == section && (scale == 0 || r.error_scale == scale)) names.push_back(r.name);
  }
  return names;
}

const BlockSpec& BlockOf(const BenchPlan& plan, const RowSpec& row) {
  return *std::find_if(plan.blocks.begin(), plan.blocks.end(), [&](const BlockSpec& b) { return b.id == row.block_id; });
}

bool Has(const std::vector<std::string>& args, const std::string& word) {
  return std::find(args.begin(), args.end(), word) != args.end();
}

TEST(QualityBenchPlanTest, MissingLidarFolderSkipsTheLidarBlocksWithAReason) {
  QualityBenchOptions o;
  o.lidar_dir = "/no/such/lidar";
  const BenchPlan plan = BuildBenchPlan(o);
  ASSERT_EQ(plan.skipped.size(), 2u);  // the default LiDAR blocks: zurich, montpellier
  EXPECT_EQ(plan.skipped[0].scene, "zurich");
  EXPECT_EQ(plan.skipped[1].scene, "montpellier");
  EXPECT_EQ(plan.skipped[0].reason, "LiDAR file not found: /no/such/lidar/lastools/zurich.las");
  for (const auto& s : plan.skipped) EXPECT_NE(s.reason.find("/no/such/lidar/"), std::string::npos) << s.reason;
  // Only the city remains: 6 methods + the ceiling per scale, then 8 ablation rows.
  const std::vector<std::string> main = {"sac", "union", "consistency", "disparity_normal", "tsdf", "multiray",
                                         "ceiling (union, no errors)"};
  EXPECT_EQ(Names(plan, "main", 1.0), main);
  EXPECT_EQ(Names(plan, "main", 2.5), main);
  EXPECT_EQ(Names(plan, "ablation").size(), 8u);

  o.lidar_dir.clear();
  const BenchPlan none = BuildBenchPlan(o);
  ASSERT_EQ(none.skipped.size(), 2u);
  EXPECT_NE(none.skipped[1].reason.find("no LiDAR folder"), std::string::npos);

  o.blocks = {"semis", "autzen"};  // by name; listed in catalogue order
  const BenchPlan sparse = BuildBenchPlan(o);
  ASSERT_EQ(sparse.skipped.size(), 2u);
  EXPECT_EQ(sparse.skipped[0].scene, "autzen");
  EXPECT_EQ(sparse.skipped[1].scene, "semis");
  EXPECT_TRUE(sparse.rows.empty() || sparse.rows.front().section == "ablation");
}

TEST(QualityBenchPlanTest, BlocksPerScaleShareOneCeilingAndTheSeed) {
  QualityBenchOptions o;
  o.blocks = {"city"};
  o.ablations = false;
  const BenchPlan plan = BuildBenchPlan(o);
  // e1, e2.5 and one no-errors block for both scales.
  ASSERT_EQ(plan.blocks.size(), 3u);
  std::vector<std::string> ids;
  for (const auto& b : plan.blocks) ids.push_back(b.id);
  EXPECT_TRUE(Has(ids, "city-small-seed7-e1-nonormals")) << ids[0];
  EXPECT_TRUE(Has(ids, "city-small-seed7-e2.5-nonormals"));
  EXPECT_TRUE(Has(ids, "city-small-seed7-noerrors-nonormals"));
  const RowSpec& ceiling1 = plan.rows[6];
  const RowSpec& ceiling25 = plan.rows[13];
  EXPECT_TRUE(ceiling1.is_ceiling);
  EXPECT_EQ(ceiling1.block_id, ceiling25.block_id);
  EXPECT_EQ(ceiling1.overrides, (std::vector<std::pair<std::string, std::string>>{{"fusion.method", "union"}}));
  const std::vector<std::string> args = BlockOf(plan, ceiling1).SimulateArgs("/b");
  EXPECT_TRUE(Has(args, "--no-errors"));
  EXPECT_FALSE(Has(args, "--error-scale"));
  const std::vector<std::string> e25 = BlockOf(plan, plan.rows[7]).SimulateArgs("/b");
  EXPECT_EQ(e25, (std::vector<std::string>{"simulate", "--preset", "small", "--seed", "7", "--out", "/b",
                                           "--error-scale", "2.5", "--no-normal-maps"}));
  EXPECT_TRUE(plan.rows[0].is_sac);
  EXPECT_EQ(plan.rows[4].overrides[0], (std::pair<std::string, std::string>{"fusion.method", "tsdf"}));
}

// --depth sgbm: the main blocks are simulated with matched depth maps; the ceiling (perfect depth) stays synthetic.
TEST(QualityBenchPlanTest, MatchedDepthBlocksKeepASyntheticCeiling) {
  QualityBenchOptions o;
  o.blocks = {"city"};
  o.error_scales = {1.0};
  o.methods = {"sac"};
  o.ablations = false;
  o.depth = "sgbm";
  const BenchPlan plan = BuildBenchPlan(o);
  ASSERT_EQ(plan.rows.size(), 2u);
  const BlockSpec& main = BlockOf(plan, plan.rows[0]);
  EXPECT_EQ(main.id, "city-small-seed7-e1-nonormals-sgbm");
  EXPECT_EQ(main.SimulateArgs("/b"), (std::vector<std::string>{"simulate", "--preset", "small", "--seed", "7", "--out",
                                                               "/b", "--error-scale", "1", "--no-normal-maps",
                                                               "--depth", "sgbm"}));
  EXPECT_EQ(BlockOf(plan, plan.rows[1]).id, "city-small-seed7-noerrors-nonormals");
  EXPECT_FALSE(Has(BlockOf(plan, plan.rows[1]).SimulateArgs("/b"), "--depth"));
  o.depth = "patchmatch";
  EXPECT_THROW(BuildBenchPlan(o), ConfigError);
}

TEST(QualityBenchPlanTest, ColmapRowsFollowTheMethodsWhenColmapIsThere) {
  QualityBenchOptions o;
  o.blocks = {"city"};
  o.error_scales = {1.0};
  o.methods = {"sac"};
  o.ablations = false;
  o.colmap_path = "/usr/bin/colmap";
  const BenchPlan plan = BuildBenchPlan(o);
  ASSERT_EQ(plan.rows.size(), 4u);
  EXPECT_EQ(plan.rows[1].kind, RowKind::kColmap);
  EXPECT_TRUE(plan.rows[1].stereo_fusion.empty());
  EXPECT_EQ(plan.rows[2].stereo_fusion, std::vector<std::string>{"max_normal_error=180"});
  EXPECT_NE(plan.rows[2].name.find("max_normal_error=180"), std::string::npos);
  EXPECT_FALSE(Has(BlockOf(plan, plan.rows[1]).SimulateArgs("/b"), "--no-normal-maps"));  // COLMAP reads them
}

TEST(QualityBenchPlanTest, AblationRowsAreOneChangeEachOnTheAblationBlock) {
  QualityBenchOptions o;
  o.blocks = {"city"};
  o.error_scales = {1.0};
  const BenchPlan plan = BuildBenchPlan(o);
  std::vector<const RowSpec*> ablation;
  for (const auto& r : plan.rows) {
    if (r.section == "ablation") ablation.push_back(&r);
  }
  ASSERT_EQ(ablation.size(), 8u);
  const std::string base = ablation[0]->block_id;
  EXPECT_EQ(base, "city-tiny-seed7-e1-nonormals");  // tiny writes consistency graphs itself
  EXPECT_TRUE(ablation[0]->is_sac);
  EXPECT_EQ(ablation[1]->overrides.back(), (std::pair<std::string, std::string>{"fusion.unary", "paper"}));
  EXPECT_EQ(ablation[3]->overrides.back(), (std::pair<std::string, std::string>{"fusion.correspondence", "dense"}));
  EXPECT_EQ(ablation[5]->overrides.back(), (std::pair<std::string, std::string>{"superpixels.algorithm", "pixels"}));
  for (int i = 0; i < 6; ++i) EXPECT_EQ(ablation[i]->block_id, base) << ablation[i]->name;
  EXPECT_TRUE(Has(BlockOf(plan, *ablation[6]).SimulateArgs("/b"), "--no-pose-errors"));
  EXPECT_EQ(ablation[6]->overrides.size(), 1u);  // plain sac
  EXPECT_TRUE(ablation[7]->is_ceiling);
  EXPECT_TRUE(Has(BlockOf(plan, *ablation[7]).SimulateArgs("/b"), "--no-errors"));
  EXPECT_EQ(ablation[7]->overrides[0].second, "union");

  o.ablation_preset = "small";  // does not write consistency graphs unless asked
  const BenchPlan small = BuildBenchPlan(o);
  const RowSpec& dense = *std::find_if(small.rows.begin(), small.rows.end(), [](const RowSpec& r) {
    return r.name == "sac, fusion.correspondence: dense";
  });
  EXPECT_TRUE(Has(BlockOf(small, dense).SimulateArgs("/b"), "--consistency-graphs"));
}

TEST(QualityBenchPlanTest, QuickIsTinyCityWithThreeMethodsAndTwoAblations) {
  QualityBenchOptions o;
  o.colmap_path = "/usr/bin/colmap";
  ApplyQuickPreset(&o);
  const BenchPlan plan = BuildBenchPlan(o);
  EXPECT_TRUE(plan.skipped.empty());
  EXPECT_EQ(Names(plan, "main"), (std::vector<std::string>{"sac", "union", "tsdf", "ceiling (union, no errors)"}));
  EXPECT_EQ(Names(plan, "ablation"), (std::vector<std::string>{"sac (default)", "sac, fusion.unary: paper"}));
  EXPECT_EQ(plan.blocks.size(), 2u);  // the ablation block is the main block
  EXPECT_EQ(plan.rows[4].block_id, plan.rows[0].block_id);
  EXPECT_EQ(plan.blocks[0].preset, "tiny");
}

TEST(QualityBenchPlanTest, BadNamesAreConfigErrorsNamingTheOption) {
  QualityBenchOptions o;
  o.blocks = {"atlantis"};
  try {
    BuildBenchPlan(o);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--blocks = 'atlantis'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("zurich"), std::string::npos) << e.what();
  }
  o.blocks = {};
  o.methods = {"sac", "magic"};
  EXPECT_THROW(BuildBenchPlan(o), ConfigError);
  o.methods = {"sac"};
  o.error_scales = {0.0};
  EXPECT_THROW(BuildBenchPlan(o), ConfigError);
  o.error_scales = {1.0};
  o.preset = "huge";
  EXPECT_THROW(BuildBenchPlan(o), ConfigError);
}

TEST(QualityBenchPlanTest, LidarBlocksFromTheSharedData) {
  const auto shared = testing::SharedDir();
  if (!shared) GTEST_SKIP() << "../shared/research-data not found (set SACFUSE_SHARED)";
  QualityBenchOptions o;
  o.lidar_dir = (*shared / "research-data" / "lidar").string();
  o.error_scales = {1.0};
  o.ablations = false;
  const BenchPlan plan = BuildBenchPlan(o);
  for (const auto& s : plan.skipped) ADD_FAILURE() << s.scene << ": " << s.reason;
  std::set<std::string> scenes;
  for (const auto& r : plan.rows) scenes.insert(r.scene);
  EXPECT_EQ(scenes, (std::set<std::string>{"city", "zurich", "montpellier"}));  // the default set
  const RowSpec& zurich = *std::find_if(plan.rows.begin(), plan.rows.end(),
                                        [](const RowSpec& r) { return r.scene == "zurich"; });
  const std::vector<std::string> args = BlockOf(plan, zurich).SimulateArgs("/b");
  EXPECT_TRUE(Has(args, "--from-las"));
  EXPECT_TRUE(Has(args, o.lidar_dir + "/lastools/zurich.las"));
}

TEST(QualityBenchPlanTest, SlugsAreFolderNames) {
  EXPECT_EQ(Slug("sac"), "sac");
  EXPECT_EQ(Slug("ceiling (union, no errors)"), "ceiling_union_no_errors");
  EXPECT_EQ(Slug("sac, fusion.unary: paper"), "sac_fusion.unary_paper");
  EXPECT_EQ(Slug("COLMAP stereo_fusion, max_normal_error=180"), "colmap_stereo_fusion_max_normal_error_180");
  EXPECT_EQ(Slug("///"), "row");
}

}  // namespace
}  // namespace sacfuse::bench
