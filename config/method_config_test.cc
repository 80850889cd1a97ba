// Config keys of the comparison methods (fusion.method consistency | disparity_normal | tsdf | multiray):
// parsed into their option structs, range-checked with the key, value, rule and line, dumped by
// --print-defaults, and part of the result-affecting settings of tiled runs.
#include <gtest/gtest.h>

#include "config/config_test_util.h"
#include "config/job_config.h"
#include "config/result_settings.h"
#include "core/error.h"

namespace sacfuse {
namespace {

std::string ErrorOf(const std::string& yaml) { return ConfigErrorOf(yaml); }

TEST(MethodConfigTest, EachMethodIsAllowedAndItsKeysReachTheOptions) {
  for (const char* method : {"sac", "union", "consistency", "disparity_normal", "tsdf", "multiray"}) {
    const JobConfig c = ParseJobConfig(std::string("input: {path: ws}\nfusion: {method: ") + method + "}\n", "job.yaml",
                                       "/base");
    EXPECT_EQ(NameOf(c.fusion.method), method);
  }
  const JobConfig c = ParseJobConfig(
      "input: {path: ws}\nfusion: {method: tsdf}\nconsistency: {depth_threshold_rel: 0.02}\n"
      "disparity_normal: {disparity_threshold_px: 0.25, normal_threshold_deg: 45, min_consistent_views: 3, "
      "normal_radius_px: 3}\ntsdf: {voxel_size_gsd: 2, truncation_gsd: 6, min_weight: 3, max_memory_gb: 1.5}\n"
      "multiray: {depth_tolerance_gsd: 2, min_rays: 3, ray_sigma_px: 0.5, depth_sigma_gsd: 0}\n",
      "job.yaml", "/base");
  EXPECT_DOUBLE_EQ(c.fusion.consistency.depth_threshold_rel, 0.02);
  EXPECT_DOUBLE_EQ(c.fusion.disparity_normal.disparity_threshold_px, 0.25);
  EXPECT_DOUBLE_EQ(c.fusion.disparity_normal.normal_threshold_deg, 45);
  EXPECT_EQ(c.fusion.disparity_normal.min_consistent_views, 3);
  EXPECT_EQ(c.fusion.disparity_normal.normal_radius_px, 3);
  EXPECT_DOUBLE_EQ(c.fusion.tsdf.voxel_size_gsd, 2);
  EXPECT_DOUBLE_EQ(c.fusion.tsdf.truncation_gsd, 6);
  EXPECT_DOUBLE_EQ(c.fusion.tsdf.min_weight, 3);
  EXPECT_DOUBLE_EQ(c.fusion.tsdf.max_memory_gb, 1.5);
  EXPECT_DOUBLE_EQ(c.fusion.multiray.depth_tolerance_gsd, 2);
  EXPECT_EQ(c.fusion.multiray.min_rays, 3);
  EXPECT_DOUBLE_EQ(c.fusion.multiray.ray_sigma_px, 0.5);
  EXPECT_DOUBLE_EQ(c.fusion.multiray.depth_sigma_gsd, 0);
}

TEST(MethodConfigTest, UnknownMethodsAndOutOfRangeValuesNameKeyLineValueAndRule) {
  std::string err = ErrorOf("input: {path: ws}\nfusion: {method: tsfd}\n");
  EXPECT_NE(err.find("fusion.method: \"tsfd\" is not one of {sac, union, consistency, disparity_normal, tsdf, "
                     "multiray}"),
            std::string::npos)
      << err;
  err = ErrorOf("input: {path: ws}\nfusion:\n  method: tsdf\ntsdf:\n  voxel_size_gsd: 2\n  truncation_gsd: 1\n");
  EXPECT_NE(err.find("job.yaml:6: tsdf.truncation_gsd = 1: must be > tsdf.voxel_size_gsd (2)"), std::string::npos)
      << err;
  err = ErrorOf("input: {path: ws}\nfusion: {method: consistency, max_neighbor_views: 0}\n"
                "consistency: {depth_threshold_rel: 0.7}\n");
  EXPECT_NE(err.find("consistency.depth_threshold_rel = 0.7: must be in (0, 0.5]"), std::string::npos) << err;
  EXPECT_NE(err.find("fusion.max_neighbor_views = 0: must be in [1, 64]"), std::string::npos) << err;
  err = ErrorOf("input: {path: ws}\nfusion: {method: multiray}\nmultiray: {min_rays: 1}\n");
  EXPECT_NE(err.find("job.yaml:3: multiray.min_rays = 1: must be in [2, 65]"), std::string::npos) << err;
  err = ErrorOf("input: {path: ws}\nfusion: {method: disparity_normal}\ndisparity_normal: {normal_threshold_deg: 0}\n");
  EXPECT_NE(err.find("disparity_normal.normal_threshold_deg = 0: must be in (0, 180]"), std::string::npos) << err;
  // A method's keys are only checked when it runs.
  EXPECT_EQ(ErrorOf("input: {path: ws}\nfusion: {method: sac}\nmultiray: {min_rays: 1}\n"), "");
}

TEST(MethodConfigTest, PrintDefaultsListsEveryMethodSectionAndTheyAffectTiledResults) {
  JobConfig c;
  const std::string dump = DumpJobConfig(c, true);
  for (const char* key : {"\nconsistency:\n", "  depth_threshold_rel: 0.01\n", "\ndisparity_normal:\n",
                          "  normal_threshold_deg: 30.0\n", "\ntsdf:\n", "  voxel_size_gsd: 1.0\n",
                          "  truncation_gsd: 8.0\n", "\nmultiray:\n", "  min_rays: 2\n"}) {
    EXPECT_NE(dump.find(key), std::string::npos) << key << " missing from:\n" << dump;
  }
  JobConfig other = c;
  other.fusion.tsdf.voxel_size_gsd = 2.0;
  EXPECT_NE(ResultSettingsHash(c), ResultSettingsHash(other));
}

}  // namespace
}  // namespace sacfuse
