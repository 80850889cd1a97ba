// Tile edge point files (io/edge_points_file.h): the coordinates come back bit for bit, and a truncated or foreign
// file is refused naming it.
#include "io/edge_points_file.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

TEST(EdgePointsFileTest, PointsComeBackBitForBit) {
  testing::TempDir dir;
  const std::string path = (dir / "3_4.dsm_edge.bin").string();
  const std::vector<Eigen::Vector3d> points = {{390019.958, 5704980.044, 112.125}, {-0.0, 1e-300, -7.5}};
  WriteEdgePointsFile(path, points);
  EXPECT_EQ(std::filesystem::file_size(path), 16u + 8u + 2u * 24u);
  const std::vector<Eigen::Vector3d> back = ReadEdgePointsFile(path);
  ASSERT_EQ(back.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(std::memcmp(&back[i][k], &points[i][k], sizeof(double)), 0);
  }
  WriteEdgePointsFile(path, {});
  EXPECT_TRUE(ReadEdgePointsFile(path).empty());
}

TEST(EdgePointsFileTest, TruncatedOrForeignFilesAreRefusedNamingTheFile) {
  testing::TempDir dir;
  const std::string path = (dir / "a.dsm_edge.bin").string();
  WriteEdgePointsFile(path, {{1, 2, 3}, {4, 5, 6}});
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 5);
  try {
    ReadEdgePointsFile(path);
    ADD_FAILURE() << "a truncated file was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a.dsm_edge.bin"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "ply\nformat binary_little_endian 1.0\n";
  EXPECT_THROW(ReadEdgePointsFile(path), InputError);
  EXPECT_THROW(ReadEdgePointsFile((dir / "missing.bin").string()), InputError);
}

}  // namespace
}  // namespace sacfuse
