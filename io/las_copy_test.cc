#include "io/las_copy.h"

#include <cstdio>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/las_reader.h"
#include "io/las_writer.h"
#include "tests/support/las_points.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using testing::ExpectSamePoints;

namespace fs = std::filesystem;
using testing::TempDir;

// A LAZ with UTM-sized coordinates on a 1 cm grid, format 1 (as the St Barth tile): the copy is LAS with the
// same format, scale and offset, and the same points.
TEST(LasCopyTest, LazToLasKeepsFormatScaleOffsetAndPoints) {
  TempDir dir;
  std::vector<LasPoint> points(70000);  // more than one LAZ chunk
  for (size_t i = 0; i < points.size(); ++i) {
    points[i].xyz = Eigen::Vector3d(515000.0 + 0.01 * static_cast<double>(i % 10000),
                                    1981000.0 + 0.01 * static_cast<double>(i / 10000), 1.5 + 0.01 * (i % 700));
    points[i].classification = static_cast<uint8_t>(i % 7);
    points[i].intensity = static_cast<uint16_t>(i);
    points[i].gps_time = 1000.0 + 0.5 * static_cast<double>(i);
  }
  LasWriterOptions options;
  options.version_minor = 2;
  options.point_format = 1;
  options.scale_xyz = Eigen::Vector3d::Constant(0.01);
  options.offset = Eigen::Vector3d(500000.0, 1900000.0, 0.0);
  options.compressed = true;
  {
    LasWriter writer((dir / "in.laz").string(), options);
    writer.WritePoints(points.data(), points.size());
    writer.Close();
  }
  EXPECT_EQ(CopyLasFile((dir / "in.laz").string(), (dir / "out.las").string(), false), points.size());
  LasHeader in_header, out_header;
  const std::vector<LasPoint> in = ReadAllLasPoints((dir / "in.laz").string(), &in_header);
  const std::vector<LasPoint> out = ReadAllLasPoints((dir / "out.las").string(), &out_header);
  EXPECT_EQ(out_header.point_format, 1);
  EXPECT_EQ(out_header.version_minor, 2);
  EXPECT_EQ(out_header.scale, in_header.scale);
  EXPECT_EQ(out_header.offset, in_header.offset);
  // Uncompressed: 227-byte header + 28-byte records, nothing hidden in the file size.
  EXPECT_EQ(fs::file_size(dir / "out.las"), out_header.offset_to_point_data + 28u * points.size());
  ExpectSamePoints(in, out);
}

TEST(LasCopyTest, UnreadableInputThrowsAndWritesNothing) {
  TempDir dir;
  {
    std::FILE* f = std::fopen((dir / "bad.laz").c_str(), "wb");
    std::fputs("LASF but not really", f);
    std::fclose(f);
  }
  EXPECT_THROW(CopyLasFile((dir / "bad.laz").string(), (dir / "out.las").string(), false), InputError);
  EXPECT_FALSE(fs::exists(dir / "out.las"));
}

// Third-party LAZ of the shared research data: the copy reads back as the same points.
TEST(LasCopyTest, SharedLazFilesCopyPointForPoint) {
  const auto shared = testing::SharedDir();
  if (!shared) GTEST_SKIP() << "../shared not found (set SACFUSE_SHARED): third-party LAZ files not checked";
  const fs::path lidar = *shared / "research-data" / "lidar";
  const std::vector<fs::path> files = {lidar / "ign_tiles" / "St_Barth_RGAF09_UTM20N_IGN_1988_SB_subset_100m.laz",
                                       *shared / "research-data" / "las_compat" / "laspy" / "plane.laz"};
  TempDir dir;
  size_t checked = 0;
  for (const fs::path& file : files) {
    if (!fs::exists(file)) continue;
    LasHeader in_header, out_header;
    const std::vector<LasPoint> in = ReadAllLasPoints(file.string(), &in_header);
    const fs::path out_path = dir / (file.stem().string() + ".las");
    EXPECT_EQ(CopyLasFile(file.string(), out_path.string(), false), in.size()) << file;
    const std::vector<LasPoint> out = ReadAllLasPoints(out_path.string(), &out_header);
    EXPECT_EQ(out_header.point_format, in_header.point_format) << file;
    EXPECT_EQ(out_header.scale, in_header.scale) << file;
    EXPECT_EQ(out_header.offset, in_header.offset) << file;
    ExpectSamePoints(in, out);
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "none of the shared LAZ files found below " << shared->string();
}

}  // namespace
}  // namespace sacfuse
