// COLMAP consistency graphs: hand-made bytes with known content, round trip, corrupt files.
#include "io/colmap_consistency_graph.h"

#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

void WriteBytes(const std::string& path, const std::string& header, const std::vector<int32_t>& values) {
  std::ofstream out(path, std::ios::binary);
  out << header;
  for (int32_t v : values) out.write(reinterpret_cast<const char*>(&v), 4);
}

TEST(ColmapConsistencyGraphTest, ReadsHandMadeFile) {
  testing::TempDir dir;
  const std::string path = (dir / "g.bin").string();
  // 3x2 image: pixel (col 2, row 0) consistent with images 4 and 7; pixel (col 0, row 1) with image 1.
  WriteBytes(path, "3&2&1&", {2, 0, 2, 4, 7, 0, 1, 1, 1});
  const ConsistencyGraph g = ReadColmapConsistencyGraph(path);
  EXPECT_EQ(g.width, 3);
  EXPECT_EQ(g.height, 2);
  auto [a, b] = g.At(0, 2);
  ASSERT_EQ(b - a, 2);
  EXPECT_EQ(a[0], 4u);
  EXPECT_EQ(a[1], 7u);
  auto [c, d] = g.At(1, 0);
  ASSERT_EQ(d - c, 1);
  EXPECT_EQ(c[0], 1u);
  auto [e, f] = g.At(1, 2);
  EXPECT_EQ(e, f);
}

TEST(ColmapConsistencyGraphTest, RoundTrip) {
  testing::TempDir dir;
  ConsistencyGraph g;
  g.width = 4;
  g.height = 3;
  g.pixel_offsets = {0, 0, 2, 2, 2, 3, 3, 3, 3, 3, 3, 3, 5};
  g.view_indices = {9, 3, 0, 5, 6};
  const std::string path = (dir / "rt.bin").string();
  WriteColmapConsistencyGraph(path, g);
  const ConsistencyGraph back = ReadColmapConsistencyGraph(path);
  EXPECT_EQ(back.pixel_offsets, g.pixel_offsets);
  EXPECT_EQ(back.view_indices, g.view_indices);
}

TEST(ColmapConsistencyGraphTest, CorruptFilesNameThePath) {
  testing::TempDir dir;
  const std::string truncated = (dir / "t.bin").string();
  WriteBytes(truncated, "3&2&1&", {2, 0, 5, 4});
  const std::string outside = (dir / "o.bin").string();
  WriteBytes(outside, "3&2&1&", {3, 0, 1, 4});
  const std::string header = (dir / "h.bin").string();
  WriteBytes(header, "3&2&", {});
  for (const auto& path : {truncated, outside, header}) {
    try {
      ReadColmapConsistencyGraph(path);
      FAIL() << "expected InputError for " << path;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sacfuse
