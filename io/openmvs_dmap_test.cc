// OpenMVS .dmap reader and writer: a file assembled byte by byte from the documented layout, the writer's bytes,
// windows, and every kind of corrupt file.
#include "io/openmvs_dmap.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/error_of.h"

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadFileBytes;
using testing::TempDir;

// Little-endian byte assembly, independent of the writer under test.
struct Bytes {
  std::string data;
  template <typename T>
  Bytes& Put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    data.append(raw, sizeof(T));
    return *this;
  }
  Bytes& Text(const std::string& s) {
    data += s;
    return *this;
  }
};

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

const std::array<double, 9> kK = {1000.0, 0.0, 319.5, 0.0, 1001.0, 239.5, 0.0, 0.0, 1.0};
const std::array<double, 9> kR = {1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0};
const std::array<double, 3> kC = {500000.25, 5400000.5, 812.75};

// A 3x2 depth map of a 6x4 image with every optional map: flags 15, image path "img/a.png", IDs {7, 3, 9}.
// Depth (row, col) = 1 + row * 3 + col; normal = (that, -that, 0.5); confidence = that / 10; views = row, col,
// 200, 255.
Bytes HandMadeFile(uint8_t flags = 15) {
  Bytes b;
  b.Text("DR").Put<uint8_t>(flags).Put<uint8_t>(0);
  b.Put<uint32_t>(6).Put<uint32_t>(4).Put<uint32_t>(3).Put<uint32_t>(2).Put<float>(1.5f).Put<float>(9.0f);
  b.Put<uint16_t>(9).Text("img/a.png");
  b.Put<uint32_t>(3).Put<uint32_t>(7).Put<uint32_t>(3).Put<uint32_t>(9);
  for (double k : kK) b.Put(k);
  for (double r : kR) b.Put(r);
  for (double c : kC) b.Put(c);
  for (int i = 0; i < 6; ++i) b.Put<float>(1.0f + i);
  if (flags & kDmapNormals) {
    for (int i = 0; i < 6; ++i) b.Put<float>(1.0f + i).Put<float>(-1.0f - i).Put<float>(0.5f);
  }
  if (flags & kDmapConfidence) {
    for (int i = 0; i < 6; ++i) b.Put<float>((1.0f + i) / 10.0f);
  }
  if (flags & kDmapViews) {
    for (int i = 0; i < 6; ++i) b.Put<uint8_t>(i / 3).Put<uint8_t>(i % 3).Put<uint8_t>(200).Put<uint8_t>(255);
  }
  return b;
}

DmapContents HandMadeContents() {
  DmapContents c;
  c.image_width = 6;
  c.image_height = 4;
  c.depth_min = 1.5f;
  c.depth_max = 9.0f;
  c.image_path = "img/a.png";
  c.view_ids = {7, 3, 9};
  c.camera.K = kK;
  c.camera.R = kR;
  c.camera.C = kC;
  c.depth = DepthMap(3, 2, 1);
  c.normals = NormalMap(3, 2, 3);
  c.confidence = Raster<float>(3, 2, 1);
  c.views = Raster<uint8_t>(3, 2, 4);
  for (int i = 0; i < 6; ++i) {
    const int row = i / 3, col = i % 3;
    c.depth.at(row, col) = 1.0f + i;
    c.normals.at(row, col, 0) = 1.0f + i;
    c.normals.at(row, col, 1) = -1.0f - i;
    c.normals.at(row, col, 2) = 0.5f;
    c.confidence.at(row, col) = (1.0f + i) / 10.0f;
    c.views.at(row, col, 0) = static_cast<uint8_t>(row);
    c.views.at(row, col, 1) = static_cast<uint8_t>(col);
    c.views.at(row, col, 2) = 200;
    c.views.at(row, col, 3) = 255;
  }
  return c;
}

using testing::InputErrorOf;

TEST(OpenMvsDmapTest, ReadsAHandMadeFileWithEveryMap) {
  TempDir dir;
  const fs::path path = dir / "depth0007.dmap";
  WriteBytes(path, HandMadeFile().data);
  const DmapHeader h = ReadDmapHeader(path.string());
  EXPECT_EQ(h.flags, 15);
  EXPECT_EQ(h.image_width, 6u);
  EXPECT_EQ(h.image_height, 4u);
  EXPECT_EQ(h.depth_width, 3u);
  EXPECT_EQ(h.depth_height, 2u);
  EXPECT_EQ(h.depth_min, 1.5f);
  EXPECT_EQ(h.depth_max, 9.0f);
  EXPECT_EQ(h.image_path, "img/a.png");
  EXPECT_EQ(h.view_ids, (std::vector<uint32_t>{7, 3, 9}));
  EXPECT_EQ(h.camera.K, kK);
  EXPECT_EQ(h.camera.R, kR);
  EXPECT_EQ(h.camera.C, kC);
  // 28 fixed + 2 + 9 (path) + 4 + 12 (IDs) + 168 (K, R, C) = 223; then 24 B depth, 72 normals, 24 conf, 24 views.
  EXPECT_EQ(h.depth_offset, 223u);
  EXPECT_EQ(h.normals_offset, 247u);
  EXPECT_EQ(h.confidence_offset, 319u);
  EXPECT_EQ(h.views_offset, 343u);
  EXPECT_EQ(h.file_size, 367u);

  const DepthMap depth = ReadDmapDepth(path.string());
  ASSERT_EQ(depth.width, 3);
  ASSERT_EQ(depth.height, 2);
  EXPECT_EQ(depth.at(0, 0), 1.0f);
  EXPECT_EQ(depth.at(0, 2), 3.0f);
  EXPECT_EQ(depth.at(1, 0), 4.0f);
  EXPECT_EQ(depth.at(1, 2), 6.0f);
  const NormalMap normals = ReadDmapNormals(path.string());
  EXPECT_EQ(normals.at(1, 1, 0), 5.0f);
  EXPECT_EQ(normals.at(1, 1, 1), -5.0f);
  EXPECT_EQ(normals.at(1, 1, 2), 0.5f);
  const Raster<float> confidence = ReadDmapConfidence(path.string());
  EXPECT_FLOAT_EQ(confidence.at(1, 2), 0.6f);
  const Raster<uint8_t> views = ReadDmapViews(path.string());
  EXPECT_EQ(views.at(1, 2, 0), 1);
  EXPECT_EQ(views.at(1, 2, 1), 2);
  EXPECT_EQ(views.at(1, 2, 2), 200);
  EXPECT_EQ(views.at(1, 2, 3), 255);
}

TEST(OpenMvsDmapTest, WriterProducesTheDocumentedBytes) {
  TempDir dir;
  const fs::path path = dir / "out" / "depth0007.dmap";  // parent folder created by the writer
  WriteDmap(path.string(), HandMadeContents());
  EXPECT_EQ(ReadFileBytes(path), HandMadeFile().data);

  // Depth only: flags 1 and the optional readers refuse, naming the file.
  DmapContents depth_only = HandMadeContents();
  depth_only.normals = {};
  depth_only.confidence = {};
  depth_only.views = {};
  const fs::path plain = dir / "depth0008.dmap";
  WriteDmap(plain.string(), depth_only);
  EXPECT_EQ(ReadFileBytes(plain), HandMadeFile(kDmapDepth).data);
  EXPECT_EQ(ReadDmapHeader(plain.string()).normals_offset, 0u);
  EXPECT_NE(InputErrorOf([&] { ReadDmapNormals(plain.string()); }).find(plain.string() + ": has no normal map"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] { ReadDmapConfidence(plain.string()); }).find("has no confidence map"), std::string::npos);
  EXPECT_NE(InputErrorOf([&] { ReadDmapViews(plain.string()); }).find("has no views map"), std::string::npos);

  // Depth + confidence only: the confidence follows the depth directly.
  DmapContents with_conf = depth_only;
  with_conf.confidence = HandMadeContents().confidence;
  WriteDmap(plain.string(), with_conf);
  EXPECT_EQ(ReadFileBytes(plain), HandMadeFile(kDmapDepth | kDmapConfidence).data);
  EXPECT_EQ(ReadDmapHeader(plain.string()).confidence_offset, 247u);
  EXPECT_FLOAT_EQ(ReadDmapConfidence(plain.string()).at(0, 1), 0.2f);
}

TEST(OpenMvsDmapTest, WindowsReadOnlyTheirPixels) {
  TempDir dir;
  DmapContents c = HandMadeContents();
  c.normals = {};
  c.confidence = {};
  c.views = {};
  c.image_width = 14;
  c.image_height = 10;
  c.depth = DepthMap(7, 5, 1);
  for (int r = 0; r < 5; ++r) {
    for (int col = 0; col < 7; ++col) c.depth.at(r, col) = 100.0f + 10.0f * r + col;
  }
  const std::string path = (dir / "depth0001.dmap").string();
  WriteDmap(path, c);
  const DepthMap whole = ReadDmapDepth(path);
  EXPECT_EQ(whole.data, c.depth.data);
  const PixelWindow window{1, 4, 2, 6};
  const DepthMap part = ReadDmapDepthWindow(path, window);
  ASSERT_EQ(part.width, 4);
  ASSERT_EQ(part.height, 3);
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 4; ++col) EXPECT_EQ(part.at(r, col), c.depth.at(r + 1, col + 2)) << r << "," << col;
  }
  const DepthMap corner = ReadDmapDepthWindow(path, PixelWindow{4, 5, 6, 7});
  EXPECT_EQ(corner.at(0, 0), 146.0f);
  EXPECT_THROW(ReadDmapDepthWindow(path, PixelWindow{0, 6, 0, 7}), Error);
  EXPECT_THROW(ReadDmapDepthWindow(path, PixelWindow{2, 2, 0, 7}), Error);
}

TEST(OpenMvsDmapTest, CorruptFilesAreInputErrorsNamingTheFileAndTheProblem) {
  TempDir dir;
  const std::string good = HandMadeFile().data;
  int n = 0;
  // Writes `bytes` to a fresh file and returns the reader's error message (which must name the file).
  auto error_for = [&](const std::string& bytes) {
    const std::string path = (dir / ("bad" + std::to_string(n++) + ".dmap")).string();
    WriteBytes(path, bytes);
    const std::string message = InputErrorOf([&] { ReadDmapHeader(path); });
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    // The depth readers report the same problem.
    EXPECT_EQ(InputErrorOf([&] { ReadDmapDepth(path); }), message);
    EXPECT_EQ(InputErrorOf([&] { ReadDmapDepthWindow(path, PixelWindow{0, 1, 0, 1}); }), message);
    return message;
  };
  auto has = [](const std::string& message, const std::string& part) {
    return message.find(part) != std::string::npos;
  };
  auto patched = [&](size_t offset, const std::string& bytes) {
    std::string b = good;
    b.replace(offset, bytes.size(), bytes);
    return b;
  };
  auto u32 = [](uint32_t v) { return Bytes().Put(v).data; };

  EXPECT_TRUE(has(InputErrorOf([&] { ReadDmapHeader((dir / "missing.dmap").string()); }), "does not exist"));
  EXPECT_TRUE(has(error_for(""), "truncated depth map header: the file has 0 bytes"));
  EXPECT_TRUE(has(error_for(good.substr(0, 27)), "truncated depth map header: the file has 27 bytes"));
  EXPECT_TRUE(has(error_for(patched(0, "XR")), "not an OpenMVS depth map: magic bytes \"XR\""));
  EXPECT_TRUE(has(error_for(patched(0, std::string("\x00\xff", 2))), "magic bytes \"\\x00\\xff\""));
  EXPECT_TRUE(has(error_for(patched(2, "\x02")), "header flags 0x02 declare no depth map"));
  // Sizes: zero, depth larger than the image, absurd (must not be allocated), image beyond int.
  EXPECT_TRUE(has(error_for(patched(12, u32(0))), "depth size 0x2 (both must be > 0)"));
  EXPECT_TRUE(has(error_for(patched(4, u32(2))), "depth size 3x2 is larger than the image size 2x4"));
  EXPECT_TRUE(has(error_for(patched(4, u32(0xffffffffu) + u32(0xffffffffu) + u32(0x7fffffffu) + u32(0x7fffffffu))),
                  "image size 4294967295x4294967295 is too large"));
  const std::string absurd = error_for(patched(4, u32(0x7fffffffu) + u32(0x7fffffffu) + u32(0x7fffffffu) +
                                                      u32(0x7fffffffu)));
  EXPECT_TRUE(has(absurd, "truncated depth map: 2147483647x2147483647 pixels of depth + normals + confidence + views"))
      << absurd;
  EXPECT_TRUE(has(absurd, "but the file has 367")) << absurd;
  // The variable-length parts.
  EXPECT_TRUE(has(error_for(good.substr(0, 29)), "ends inside the image path length"));
  EXPECT_TRUE(has(error_for(good.substr(0, 35)), "ends inside the image path (bytes 30..39)"));
  EXPECT_TRUE(has(error_for(good.substr(0, 41)), "ends inside the view ID count"));
  EXPECT_TRUE(has(error_for(good.substr(0, 50)), "ends inside the view IDs"));
  EXPECT_TRUE(has(error_for(good.substr(0, 100)), "ends inside the camera (K, R, C)"));
  EXPECT_TRUE(has(error_for(patched(39, u32(0))), "0 view IDs (must be 1..255"));
  EXPECT_TRUE(has(error_for(patched(39, u32(1000000))), "1000000 view IDs"));
  EXPECT_TRUE(has(error_for(patched(28, Bytes().Put<uint16_t>(60000).data)), "ends inside the image path"));
  // The maps.
  EXPECT_TRUE(has(error_for(good.substr(0, good.size() - 1)),
                  "truncated depth map: 3x2 pixels of depth + normals + confidence + views (flags 0x0f) from byte "
                  "223 need 367 bytes in all, but the file has 366"));
  EXPECT_TRUE(has(error_for(good.substr(0, 230)), "but the file has 230"));
  EXPECT_TRUE(has(error_for(good + "x"), "mismatched depth map"));
  EXPECT_TRUE(has(error_for(patched(2, "\x01")), "mismatched depth map: 3x2 pixels of depth (flags 0x01)"));
  EXPECT_TRUE(has(error_for(patched(2, "\x13")), "mismatched depth map: 3x2 pixels of depth + normals (flags 0x13)"));
  EXPECT_TRUE(has(error_for(patched(2, "\x13")), "unknown bits 0x10"));
}

TEST(OpenMvsDmapTest, UnknownFlagBitsWithoutDataAreAccepted) {
  // Forks may mark files with extra flag bits; the size check decides whether data follows.
  TempDir dir;
  const fs::path path = dir / "depth0000.dmap";
  std::string bytes = HandMadeFile(kDmapDepth).data;
  bytes[2] = 0x11;
  WriteBytes(path, bytes);
  EXPECT_EQ(ReadDmapHeader(path.string()).flags, 0x11);
  EXPECT_EQ(ReadDmapDepth(path.string()).at(1, 2), 6.0f);
}

TEST(OpenMvsDmapTest, WriterRejectsBadContentsAndLeavesNoFile) {
  TempDir dir;
  const std::string path = (dir / "depth0000.dmap").string();
  auto rejects = [&](DmapContents c, const std::string& part) {
    try {
      WriteDmap(path, c);
      ADD_FAILURE() << "accepted: " << part;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  DmapContents c = HandMadeContents();
  c.depth = DepthMap();
  rejects(c, "depth raster must be non-empty");
  c = HandMadeContents();
  c.image_width = 2;
  rejects(c, "image size 2x4 is smaller than the depth map 3x2");
  c = HandMadeContents();
  c.view_ids.clear();
  rejects(c, "0 view IDs");
  c = HandMadeContents();
  c.view_ids.assign(256, 1);
  rejects(c, "256 view IDs");
  c = HandMadeContents();
  c.normals = NormalMap(3, 2, 1);
  rejects(c, "normal map is 3x2x1, expected 3x2x3");
  c = HandMadeContents();
  c.views = Raster<uint8_t>(2, 2, 4);
  rejects(c, "views map is 2x2x4");
  c = HandMadeContents();
  c.image_path.assign(70000, 'a');
  rejects(c, "image path longer than 65535 bytes");
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace sacfuse
