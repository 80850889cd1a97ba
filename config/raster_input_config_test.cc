// Config keys of the `rasters` input (input.cameras, input.depth_kind): parsing, paths and messages.
#include <gtest/gtest.h>

#include "config/config_test_util.h"
#include "config/job_config.h"
#include "core/error.h"

namespace sacfuse {
namespace {

std::string ErrorOf(const std::string& yaml) { return ConfigErrorOf(yaml); }

TEST(RasterInputConfigTest, KeysParseWithDefaultsAndResolvedPaths) {
  const JobConfig d = ParseJobConfig("input: {format: rasters, path: blk}\n", "job.yaml", "/base");
  EXPECT_EQ(d.input.format, "rasters");
  EXPECT_EQ(d.input.cameras, "");
  EXPECT_EQ(d.input.depth_kind, "z");
  const JobConfig c =
      ParseJobConfig("crs: EPSG:25832\ninput: {format: rasters, path: blk, cameras: blk/cams.CSV, depth_kind: range}\n",
                     "job.yaml", "/base");
  EXPECT_EQ(c.input.cameras, "/base/blk/cams.CSV");
  EXPECT_EQ(c.input.depth_kind, "range");
  EXPECT_EQ(c.crs, "EPSG:25832");
  // The dump lists both keys and parses back.
  const std::string dumped = DumpJobConfig(c, true);
  EXPECT_NE(dumped.find("cameras:"), std::string::npos);
  EXPECT_NE(dumped.find("depth_kind: \"range\""), std::string::npos) << dumped;
  EXPECT_EQ(ParseJobConfig(dumped, "dump.yaml", "/elsewhere").input.cameras, "/base/blk/cams.CSV");
}

TEST(RasterInputConfigTest, BadValuesNameKeyLineAndRule) {
  std::string err = ErrorOf("input:\n  format: rasters\n  path: b\n  depth_kind: disparity\n");
  EXPECT_NE(err.find("job.yaml:4: input.depth_kind: \"disparity\" is not one of {z, range}"), std::string::npos) << err;
  err = ErrorOf("input:\n  format: rasters\n  path: b\n  cameras: cams.txt\n");
  EXPECT_NE(err.find("job.yaml:4: input.cameras = /base/cams.txt: must be a .yaml, .yml or .csv camera file"),
            std::string::npos)
      << err;
  err = ErrorOf("input:\n  format: colmap\n  path: b\n  cameras: c.yaml\n  depth_kind: range\n");
  EXPECT_NE(err.find("job.yaml:4: input.cameras = /base/c.yaml: only read by input.format: rasters"), std::string::npos)
      << err;
  EXPECT_NE(err.find("job.yaml:5: input.depth_kind = range: only read by input.format: rasters"), std::string::npos)
      << err;
}

}  // namespace
}  // namespace sacfuse
