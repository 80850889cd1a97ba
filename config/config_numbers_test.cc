// The one rule every number of the config obeys (config/config_schema.h): finite and at most 1e9 in magnitude,
// whatever the key; and repeated YAML keys are errors naming the file, line and key (issue 14: `.inf` passed
// validation, tiling.tile_size_m: .inf wrote a 0-point cloud; a repeated key silently won).
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "config/config_schema.h"
#include "config/config_test_util.h"
#include "config/job_config.h"

namespace sacfuse {
namespace {

std::string ErrorOf(const std::string& yaml) { return ConfigErrorOf(yaml); }

bool Contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ConfigNumbersTest, InfiniteAndNanValuesNameKeyValueAndRule) {
  const std::string err = ErrorOf(
      "input: {path: ws}\n"
      "tiling:\n"
      "  tile_size_m: .inf\n"
      "  z_min_m: -.inf\n"
      "  z_max_m: .inf\n"
      "  halo_m: .nan\n");
  EXPECT_TRUE(Contains(err, "job.yaml:3: tiling.tile_size_m = .inf: must be a finite number")) << err;
  EXPECT_TRUE(Contains(err, "job.yaml:4: tiling.z_min_m = -.inf: must be a finite number")) << err;
  EXPECT_TRUE(Contains(err, "job.yaml:5: tiling.z_max_m = .inf: must be a finite number")) << err;
  EXPECT_TRUE(Contains(err, "job.yaml:6: tiling.halo_m = .nan: must be a finite number")) << err;
}

TEST(ConfigNumbersTest, HugeValuesAreOutOfTheSharedRange) {
  const std::string err = ErrorOf("input: {path: ws}\ntiling: {z_max_m: 1e300}\nsuperpixels: {ruler: 1e30}\n");
  EXPECT_TRUE(Contains(err, "job.yaml:2: tiling.z_max_m = 1e300: must be a finite number in [-1e9, 1e9]")) << err;
  EXPECT_TRUE(Contains(err, "job.yaml:3: superpixels.ruler = 1e30: must be a finite number in [-1e9, 1e9]")) << err;
}

TEST(ConfigNumbersTest, ListItemsObeyTheRuleToo) {
  const std::string err = ErrorOf("input: {path: ws}\nevaluation: {tau_gsd: [2, .inf]}\n");
  EXPECT_TRUE(Contains(err, "job.yaml:2: evaluation.tau_gsd = .inf: must be a finite number")) << err;
}

// Every numeric key of the schema, not a list of chosen ones: set each to .inf in turn.
TEST(ConfigNumbersTest, EveryNumericKeyRefusesInfinity) {
  int numeric_keys = 0;
  for (const auto& [key, value] : JobConfigValues(JobConfig())) {
    const bool list = !value.empty() && value[0] == '[';
    char* end = nullptr;
    std::strtod(value.c_str(), &end);
    const bool number = !value.empty() && value[0] != '"' && end == value.c_str() + value.size();
    if (!list && !number) continue;
    ++numeric_keys;
    const size_t dot = key.find('.');
    ASSERT_NE(dot, std::string::npos) << key;
    const std::string section = key.substr(0, dot);
    const std::string item = "  " + key.substr(dot + 1) + ": " + (list ? "[.inf]" : ".inf") + "\n";
    const std::string yaml = section == "input" ? "input:\n  path: ws\n" + item  // input.origin_m
                                                : "input: {path: ws}\n" + section + ":\n" + item;
    const std::string err = ErrorOf(yaml);
    const bool whole = !list && value.find_first_of(".eEn") == std::string::npos;  // AddInt (doubles print "x.0")
    const std::string expected = whole ? key + ": expected a whole number, got \".inf\""
                                       : key + " = .inf: must be a finite number";
    EXPECT_TRUE(Contains(err, expected)) << key << "\n" << yaml << "\n" << err;
  }
  EXPECT_GT(numeric_keys, 40);
}

TEST(ConfigNumbersTest, FiniteValuesInRangeStillParse) {
  const JobConfig c = ParseJobConfig("input: {path: ws}\ntiling: {z_min_m: -1e9, z_max_m: 1e9, tile_size_m: 250}\n",
                                     "job.yaml", "/base");
  EXPECT_DOUBLE_EQ(c.tiling.z_max_m, kMaxConfigMagnitude);
  EXPECT_DOUBLE_EQ(c.tiling.tile_size_m, 250.0);
}

TEST(ConfigNumbersTest, RepeatedKeyNamesFileLineKeyAndFirstLine) {
  const std::string err = ErrorOf(
      "input: {path: ws}\n"
      "tiling:\n"
      "  tile_size_m: 20\n"
      "  halo_m: 3\n"
      "  tile_size_m: 40\n");
  EXPECT_TRUE(Contains(err, "job.yaml:5: tiling.tile_size_m: duplicate key (first on line 3)")) << err;
}

TEST(ConfigNumbersTest, RepeatedSectionsAndFlowKeysAreErrors) {
  const std::string sections = ErrorOf("input: {path: ws}\ntiling: {halo_m: 3}\ntiling: {tile_size_m: 40}\n");
  EXPECT_TRUE(Contains(sections, "job.yaml:3: tiling: duplicate key (first on line 2)")) << sections;
  const std::string flow = ErrorOf("input: {path: ws, path: other}\n");
  EXPECT_TRUE(Contains(flow, "job.yaml:1: input.path: duplicate key (first on line 1)")) << flow;
}

}  // namespace
}  // namespace sacfuse
