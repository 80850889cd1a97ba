// Tests of YAML config parsing: defaults, paths, and the exact error messages users see.
#include "config/config_test_util.h"
#include "config/job_config.h"

#include <sys/stat.h>

#include <filesystem>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

std::string ErrorOf(const std::string& yaml) { return ConfigErrorOf(yaml); }

TEST(JobConfigTest, MinimalConfigTakesDefaultsAndResolvesPaths) {
  const JobConfig c = ParseJobConfig("input: {format: colmap, path: ws}\noutput: {dir: out}\n", "job.yaml", "/base");
  EXPECT_EQ(c.input.path, "/base/ws");
  EXPECT_EQ(c.output.dir, "/base/out");
  EXPECT_EQ(c.output.las_version, "1.4");
  EXPECT_DOUBLE_EQ(c.output.scale_m, 0.001);
  EXPECT_EQ(c.fusion.method, FusionMethodKind::kSac);
  EXPECT_EQ(c.evaluation.tau_gsd, (std::vector<double>{2.0, 5.0}));
}

TEST(JobConfigTest, AbsolutePathsStay) {
  const JobConfig c = ParseJobConfig("input: {path: /data/ws}\n", "job.yaml", "/base");
  EXPECT_EQ(c.input.path, "/data/ws");
}

TEST(JobConfigTest, UnknownKeyNamesKeyLineAndAlternatives) {
  const std::string err = ErrorOf("input:\n  path: ws\n  fromat: colmap\n");
  EXPECT_NE(err.find("job.yaml:3: input.fromat: unknown key"), std::string::npos) << err;
  EXPECT_NE(err.find("format"), std::string::npos) << err;
}

TEST(JobConfigTest, UnknownSectionIsAnError) {
  const std::string err = ErrorOf("input: {path: ws}\ntiling_typo: {a: 1}\n");
  EXPECT_NE(err.find("job.yaml:2: tiling_typo: unknown key"), std::string::npos) << err;
}

TEST(JobConfigTest, WrongTypeNamesKeyLineAndValue) {
  const std::string err = ErrorOf("input: {path: ws}\noutput:\n  scale_m: fine\n");
  EXPECT_NE(err.find("job.yaml:3: output.scale_m: expected a number, got \"fine\""), std::string::npos) << err;
}

TEST(JobConfigTest, SectionGivenAsScalarIsAnError) {
  const std::string err = ErrorOf("input: ws\n");
  EXPECT_NE(err.find("job.yaml:1: input: expected a mapping"), std::string::npos) << err;
}

TEST(JobConfigTest, EnumValueOutsideTheAllowedSet) {
  const std::string err = ErrorOf("input: {path: ws, format: pmvs}\n");
  EXPECT_NE(err.find("input.format: \"pmvs\" is not one of {colmap"), std::string::npos) << err;
}

TEST(JobConfigTest, OutOfRangeValuesNameKeyValueAndRule) {
  const std::string err = ErrorOf("input: {path: ws}\noutput: {scale_m: 0.003}\nresources: {memory_gb: -1}\n");
  EXPECT_NE(err.find("job.yaml:2: output.scale_m = 0.003: must be 10^k x {1, 0.5, 0.25}"), std::string::npos) << err;
  EXPECT_NE(err.find("job.yaml:3: resources.memory_gb = -1: must be > 0"), std::string::npos) << err;
}

TEST(JobConfigTest, FusionAndSuperpixelRulesAreReportedTogetherWithLines) {
  const std::string err =
      ErrorOf("input: {path: ws}\nfusion:\n  tau_m: 0\n  unary: quality\nsuperpixels:\n  region_size_px: 1\n");
  EXPECT_NE(err.find("job.yaml:3: fusion.tau_m = 0: must be > 0"), std::string::npos) << err;
  EXPECT_NE(err.find("job.yaml:6: superpixels.region_size_px = 1: must be in [2, 128]"), std::string::npos) << err;
}

TEST(JobConfigTest, MissingInputPathIsAnError) {
  const std::string err = ErrorOf("output: {dir: out}\n");
  EXPECT_NE(err.find("input.path is empty"), std::string::npos) << err;
}

TEST(JobConfigTest, BrokenYamlReportsTheLine) {
  const std::string err = ErrorOf("input: {path: ws\noutput: [\n");
  EXPECT_NE(err.find("not valid YAML"), std::string::npos) << err;
}

// yaml-cpp reads the first document of a stream only: keys after a "---" line were silently ignored (issue 50:
// tau_m stayed 2.0, exit 0). A second document is an error naming the file and its "---" line.
TEST(JobConfigTest, SecondYamlDocumentIsAnErrorNamingItsLine) {
  const std::string err = ErrorOf("input: {path: ws}\nfusion: {tau_m: 2.0}\n---\nfusion: {tau_m: 1.0}\n");
  EXPECT_NE(err.find("job.yaml:3: a second YAML document starts here"), std::string::npos) << err;
  EXPECT_NE(err.find("put them into the first document"), std::string::npos) << err;
  const std::string after_start = ErrorOf("---\ninput: {path: ws}\n--- # more\nfusion: {tau_m: 1.0}\n");
  EXPECT_NE(after_start.find("job.yaml:3: a second YAML document"), std::string::npos) << after_start;
  // A leading "---" and an empty document after the only one are fine.
  EXPECT_EQ(ParseJobConfig("---\ninput: {path: ws}\n", "job.yaml", "/b").input.path, "/b/ws");
  EXPECT_EQ(ParseJobConfig("input: {path: ws}\n---\n", "job.yaml", "/b").input.path, "/b/ws");
}

TEST(JobConfigTest, DumpWithCommentsParsesBackToTheSameConfig) {
  JobConfig c;
  c.input.path = "/x/ws";
  c.output.scale_m = 0.0025;
  c.evaluation.tau_gsd = {1.0, 3.5};
  const std::string text = DumpJobConfig(c, true);
  EXPECT_NE(text.find("# LAS coordinate quantum, metres"), std::string::npos) << text;
  const JobConfig back = ParseJobConfig(text, "dump.yaml", "");
  EXPECT_EQ(back.input.path, "/x/ws");
  EXPECT_DOUBLE_EQ(back.output.scale_m, 0.0025);
  EXPECT_EQ(back.evaluation.tau_gsd, (std::vector<double>{1.0, 3.5}));
  EXPECT_EQ(DumpJobConfig(back, false), DumpJobConfig(c, false));
}

TEST(JobConfigTest, MissingFileIsAConfigError) {
  EXPECT_THROW(LoadJobConfig("/nonexistent/sacfuse.yaml"), ConfigError);
}

// A FIFO in place of the config is refused at once instead of blocking the run forever (io/input_file.h).
TEST(JobConfigTest, ConfigThatIsNotARegularFileIsRefused) {
  sacfuse::testing::TempDir dir;
  const std::string fifo = (dir / "job.yaml").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  try {
    LoadJobConfig(fifo);
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(fifo + ": cannot read config file: it is a FIFO (named pipe), not a regular "
                                                "file"),
              std::string::npos)
        << e.what();
  }
  const std::string loop = (dir / "loop.yaml").string();
  std::filesystem::create_symlink(loop, loop);
  try {
    LoadJobConfig(loop);
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("Too many levels of symbolic links"), std::string::npos) << e.what();
  }
}

TEST(JobConfigTest, TilingKeysParseAndValidate) {
  const JobConfig c = ParseJobConfig(
      "input: {path: ws}\ntiling: {tile_size_m: 250, halo_m: 8, z_min_m: -5, z_max_m: 400}\n", "job.yaml", "/base");
  EXPECT_DOUBLE_EQ(c.tiling.tile_size_m, 250.0);
  EXPECT_DOUBLE_EQ(c.tiling.halo_m, 8.0);
  EXPECT_EQ(c.tiling.window_margin_px, 16);
  EXPECT_DOUBLE_EQ(JobConfig().tiling.tile_size_m, 0.0);  // untiled by default
  const std::string err = ErrorOf("input: {path: ws}\ntiling:\n  tile_size_m: -1\n  halo_m: -2\n");
  EXPECT_NE(err.find("job.yaml:3: tiling.tile_size_m = -1: must be >= 0"), std::string::npos) << err;
  EXPECT_NE(err.find("job.yaml:4: tiling.halo_m = -2: must be >= 0"), std::string::npos) << err;
  const std::string dense = ErrorOf("input: {path: ws}\ntiling: {tile_size_m: 20}\nfusion: {correspondence: dense}\n");
  EXPECT_NE(dense.find("dense is not supported by tiled runs"), std::string::npos) << dense;
}

}  // namespace
}  // namespace sacfuse
