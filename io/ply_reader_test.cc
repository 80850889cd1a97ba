#include "io/ply_reader.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using testing::TempDir;

template <typename T>
void Put(std::string* out, T value, bool big_endian = false) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian) std::reverse(bytes, bytes + sizeof(T));
  out->append(bytes, sizeof(T));
}

std::string WriteFile(const TempDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// Two vertices in an unusual layout: colour first, a double y, an unused property, normals out of order, and a
// "camera" element before the vertices (fixed size, skipped).
std::string OddOrderPly(bool big_endian) {
  std::string h = "ply\r\nformat " + std::string(big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\r\ncomment written by hand\nelement camera 1\nproperty float view_px\nproperty uchar k\n"
                  "element vertex 2\nproperty uchar blue\nproperty float z\nproperty double y\n"
                  "property uchar green\nproperty float nz\nproperty int quality\nproperty float x\n"
                  "property float nx\nproperty uchar red\nproperty float ny\n"
                  "element face 0\nproperty list uchar int vertex_indices\nend_header\n";
  Put<float>(&h, 1.5f, big_endian);
  Put<uint8_t>(&h, 7);
  const double ys[2] = {5705123.25, -2.5};
  for (int i = 0; i < 2; ++i) {
    Put<uint8_t>(&h, static_cast<uint8_t>(30 + i));                 // blue
    Put<float>(&h, 100.125f + i, big_endian);                        // z
    Put<double>(&h, ys[i], big_endian);                              // y
    Put<uint8_t>(&h, static_cast<uint8_t>(20 + i));                 // green
    Put<float>(&h, 0.75f, big_endian);                               // nz
    Put<int32_t>(&h, -42, big_endian);                               // quality
    Put<float>(&h, 12.5f * (i + 1), big_endian);                     // x
    Put<float>(&h, 0.5f, big_endian);                                // nx
    Put<uint8_t>(&h, static_cast<uint8_t>(10 + i));                 // red
    Put<float>(&h, -0.25f, big_endian);                              // ny
  }
  return h;
}

void ExpectOddOrderVertices(const std::string& path) {
  PlyVertexReader ply(path);
  EXPECT_EQ(ply.vertex_count(), 2u);
  EXPECT_TRUE(ply.has_normals());
  EXPECT_TRUE(ply.has_colour());
  EXPECT_EQ(ply.vertex_properties().front(), "blue");
  std::vector<PlyVertex> v;
  ASSERT_EQ(ply.Read(&v, 1), 1u);
  EXPECT_EQ(v[0].xyz, Eigen::Vector3d(12.5, 5705123.25, 100.125));
  EXPECT_EQ(v[0].normal, Eigen::Vector3f(0.5f, -0.25f, 0.75f));
  EXPECT_EQ(v[0].rgb, (std::array<uint8_t, 3>{10, 20, 30}));
  ASSERT_EQ(ply.Read(&v, 100), 1u);
  EXPECT_EQ(v[0].xyz, Eigen::Vector3d(25.0, -2.5, 101.125));
  EXPECT_EQ(v[0].rgb, (std::array<uint8_t, 3>{11, 21, 31}));
  EXPECT_EQ(ply.Read(&v, 100), 0u);
  EXPECT_TRUE(v.empty());
}

TEST(PlyReaderTest, ReadsPropertiesInAnyOrderAndType) {
  TempDir dir;
  ExpectOddOrderVertices(WriteFile(dir, "odd.ply", OddOrderPly(false)));
}

TEST(PlyReaderTest, ReadsBigEndianToo) {
  TempDir dir;
  ExpectOddOrderVertices(WriteFile(dir, "odd_be.ply", OddOrderPly(true)));
}

TEST(PlyReaderTest, ReadsColmapsFusedPlyLayout) {
  // COLMAP 3.8 WriteBinaryPlyPoints: x y z nx ny nz as float, red green blue as uchar.
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  for (int i = 0; i < 3; ++i) {
    for (float f : {1.0f * i, 2.0f * i, 3.0f * i, 0.0f, 0.0f, 1.0f}) Put<float>(&ply, f);
    for (uint8_t c : {uint8_t(200), uint8_t(100), uint8_t(i)}) Put<uint8_t>(&ply, c);
  }
  TempDir dir;
  PlyVertexReader reader(WriteFile(dir, "fused.ply", ply));
  std::vector<PlyVertex> v;
  ASSERT_EQ(reader.Read(&v, 10), 3u);
  EXPECT_EQ(v[2].xyz, Eigen::Vector3d(2, 4, 6));
  EXPECT_EQ(v[2].normal, Eigen::Vector3f(0, 0, 1));
  EXPECT_EQ(v[2].rgb, (std::array<uint8_t, 3>{200, 100, 2}));
}

TEST(PlyReaderTest, WithoutNormalsAndColourGivesZeros) {
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\n"
                    "property double y\nproperty double z\nend_header\n";
  for (double d : {1.0, 2.0, 3.0}) Put<double>(&ply, d);
  TempDir dir;
  PlyVertexReader reader(WriteFile(dir, "xyz.ply", ply));
  EXPECT_FALSE(reader.has_normals());
  EXPECT_FALSE(reader.has_colour());
  std::vector<PlyVertex> v;
  ASSERT_EQ(reader.Read(&v, 10), 1u);
  EXPECT_EQ(v[0].xyz, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(v[0].rgb, (std::array<uint8_t, 3>{0, 0, 0}));
}

// Throws InputError; returns its message.
std::string OpenError(const std::string& path) {
  try {
    PlyVertexReader reader(path);
    std::vector<PlyVertex> v;
    while (reader.Read(&v, 1) > 0) {
    }
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

TEST(PlyReaderTest, TruncatedFileThrowsNamingTheFile) {
  const std::string full = OddOrderPly(false);
  TempDir dir;
  const std::string path = WriteFile(dir, "truncated.ply", full.substr(0, full.size() - 5));
  const std::string message = OpenError(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  // A header cut before end_header too.
  const std::string header_cut = WriteFile(dir, "header_cut.ply", full.substr(0, 40));
  EXPECT_NE(OpenError(header_cut).find(header_cut), std::string::npos);
}

TEST(PlyReaderTest, RejectsWhatItCannotRead) {
  TempDir dir;
  EXPECT_NE(OpenError(WriteFile(dir, "a.ply", "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n")).find("ASCII"),
            std::string::npos);
  EXPECT_NE(OpenError(WriteFile(dir, "b.ply", "PLY?\n")).find("not a PLY"), std::string::npos);
  EXPECT_NE(OpenError(WriteFile(dir, "c.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 0\n"
                                              "property float x\nproperty float y\nend_header\n"))
                .find("\"z\""),
            std::string::npos);
  EXPECT_NE(OpenError(WriteFile(dir, "d.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 0\n"
                                              "property half x\nend_header\n"))
                .find("unknown property type"),
            std::string::npos);
  EXPECT_NE(OpenError((dir / "missing.ply").string()).find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace sacfuse
