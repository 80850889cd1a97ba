#include "tools/bench/colmap_fusion.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

// The value following `flag` in argv ("" when absent); counts occurrences in *count.
std::string ValueOf(const std::vector<std::string>& argv, const std::string& flag, int* count = nullptr) {
  std::string value;
  int n = 0;
  for (size_t i = 0; i + 1 < argv.size(); ++i) {
    if (argv[i] == flag) {
      value = argv[i + 1];
      ++n;
    }
  }
  if (count) *count = n;
  return value;
}

TEST(ColmapFusionTest, CommandCarriesTheJobsThreadsAndMemory) {
  ColmapFusionRequest request;
  request.threads = 0;
  request.memory_gb = 2.5;
  request.input_type = "photometric";
  const auto argv = StereoFusionCommand(request, "/usr/bin/colmap", "/w", "/w/fused.ply");
  EXPECT_EQ(argv[0], "/usr/bin/colmap");
  EXPECT_EQ(argv[1], "stereo_fusion");
  EXPECT_EQ(ValueOf(argv, "--workspace_path"), "/w");
  EXPECT_EQ(ValueOf(argv, "--workspace_format"), "COLMAP");
  EXPECT_EQ(ValueOf(argv, "--input_type"), "photometric");
  EXPECT_EQ(ValueOf(argv, "--output_path"), "/w/fused.ply");
  EXPECT_EQ(ValueOf(argv, "--StereoFusion.num_threads"), "-1");  // 0 = all cores
  EXPECT_EQ(ValueOf(argv, "--StereoFusion.cache_size"), "2.5");
  EXPECT_EQ(ValueOf(argv, "--StereoFusion.use_cache"), "0");
  request.threads = 3;
  request.use_cache = true;
  const auto cached = StereoFusionCommand(request, "colmap", "/w", "/w/fused.ply");
  EXPECT_EQ(ValueOf(cached, "--StereoFusion.num_threads"), "3");
  EXPECT_EQ(ValueOf(cached, "--StereoFusion.use_cache"), "1");
}

TEST(ColmapFusionTest, ExtraOptionsAreAddedOrReplaceOursOnce) {
  ColmapFusionRequest request;
  request.threads = 2;
  request.stereo_fusion_options = {ParseStereoFusionOption("max_normal_error=180"),
                                   ParseStereoFusionOption("num_threads=1")};
  const auto argv = StereoFusionCommand(request, "colmap", "/w", "/w/fused.ply");
  int count = 0;
  EXPECT_EQ(ValueOf(argv, "--StereoFusion.num_threads", &count), "1");
  EXPECT_EQ(count, 1) << "COLMAP refuses an option given twice";
  EXPECT_EQ(ValueOf(argv, "--StereoFusion.max_normal_error", &count), "180");
  EXPECT_EQ(count, 1);
}

TEST(ColmapFusionTest, OptionSyntaxIsChecked) {
  EXPECT_EQ(ParseStereoFusionOption("min_num_pixels=2"), std::make_pair(std::string("min_num_pixels"), std::string("2")));
  for (const char* bad : {"max_normal_error", "=3", "max_normal_error=", "StereoFusion.x=1", "a b=1", "--x=1"}) {
    EXPECT_THROW(ParseStereoFusionOption(bad), ConfigError) << bad;
  }
}

TEST(ColmapFusionTest, MissingBinaryIsAConfigErrorWithAdvice) {
  try {
    RequireColmapBinary("sacfuse-no-such-colmap");
    FAIL() << "no exception";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("not on PATH"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("apt-get install colmap"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sacfuse
