// Row configs of `sacfuse bench`: the block's sacfuse.yaml with absolute paths, the row's output folder and keys.
#include <fstream>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/test_support.h"
#include "tools/bench/quality_bench_config.h"

namespace sacfuse::bench {
namespace {

// What `sacfuse simulate` writes (block style, paths relative to the file).
const char* const kBlockConfig =
    "# Written by `sacfuse simulate`; paths are relative to this file.\n"
    "input:\n  path: .\n  format: colmap\n"
    "output:\n  dir: out\n"
    "fusion:\n  method: sac\n"
    "evaluation:\n  reference: reference.las\n  mask: eval_mask.png\n  gsd_m: 0.2\n  tau_gsd: [2, 5]\n";

class QualityBenchConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    block_ = dir_ / "block";
    std::filesystem::create_directories(block_);
    std::ofstream(block_ / "sacfuse.yaml") << kBlockConfig;
  }
  testing::TempDir dir_;
  std::filesystem::path block_;
};

TEST_F(QualityBenchConfigTest, PathsBecomeAbsoluteAndKeysAreSet) {
  RowConfigRequest r;
  r.block_config = (block_ / "sacfuse.yaml").string();
  r.output_dir = (dir_ / "rows" / "tsdf" / "out").string();
  r.overrides = {{"fusion.method", "tsdf"}, {"superpixels.algorithm", "pixels"}, {"tsdf.voxel_size_gsd", "2"}};
  const YAML::Node y = YAML::Load(MakeRowConfig(r));
  EXPECT_EQ(y["input"]["path"].as<std::string>(), block_.string());
  EXPECT_EQ(y["input"]["format"].as<std::string>(), "colmap");
  EXPECT_EQ(y["output"]["dir"].as<std::string>(), r.output_dir);
  EXPECT_EQ(y["fusion"]["method"].as<std::string>(), "tsdf");
  EXPECT_EQ(y["superpixels"]["algorithm"].as<std::string>(), "pixels");
  EXPECT_DOUBLE_EQ(y["tsdf"]["voxel_size_gsd"].as<double>(), 2.0);
  EXPECT_TRUE(y["tsdf"]["voxel_size_gsd"].IsScalar());
  EXPECT_EQ(y["evaluation"]["reference"].as<std::string>(), (block_ / "reference.las").string());
  EXPECT_EQ(y["evaluation"]["mask"].as<std::string>(), (block_ / "eval_mask.png").string());

  r.keep_evaluation = false;
  EXPECT_FALSE(YAML::Load(MakeRowConfig(r))["evaluation"]);
}

TEST_F(QualityBenchConfigTest, BlockEvaluationWithAbsolutePaths) {
  const BlockEvaluation e = ReadBlockEvaluation((block_ / "sacfuse.yaml").string());
  EXPECT_EQ(e.reference, (block_ / "reference.las").string());
  EXPECT_EQ(e.mask, (block_ / "eval_mask.png").string());
  EXPECT_DOUBLE_EQ(e.gsd_m, 0.2);
  EXPECT_EQ(e.tau_gsd, (std::vector<double>{2.0, 5.0}));
  EXPECT_FALSE(e.align);
}

TEST_F(QualityBenchConfigTest, BadInputsAreErrorsNamingTheFileOrKey) {
  RowConfigRequest r;
  r.block_config = (block_ / "missing.yaml").string();
  r.output_dir = (dir_ / "out").string();
  EXPECT_NE(testing::InputErrorOf([&] { MakeRowConfig(r); }).find("missing.yaml"), std::string::npos);
  std::ofstream(block_ / "list.yaml") << "- a\n- b\n";
  r.block_config = (block_ / "list.yaml").string();
  EXPECT_NE(testing::InputErrorOf([&] { MakeRowConfig(r); }).find("not a YAML mapping"), std::string::npos);
  r.block_config = (block_ / "sacfuse.yaml").string();
  r.overrides = {{"fusion.method.deeper", "x"}};
  try {
    MakeRowConfig(r);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("fusion.method.deeper"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sacfuse::bench
