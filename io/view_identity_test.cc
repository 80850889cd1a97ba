// A view's identity (io/view_identity.h): files by size, mtime and the edges' FNV-1a; the camera by its values;
// what changed, in words; the JSON round trip; and the hashing throughput of the sampled and the full hash.
#include "io/view_identity.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/file_checksum.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

void Write(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

std::string Pattern(size_t n) {
  std::string s(n, '\0');
  for (size_t i = 0; i < n; ++i) s[i] = static_cast<char>((i * 2654435761u) >> 13);
  return s;
}

TEST(ViewIdentityTest, FilesAreIdentifiedBySizeTimeAndTheirEdges) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "depth.bin";
  EXPECT_FALSE(IdentifyFile((dir.path() / "missing.bin").string()).exists);
  EXPECT_FALSE(IdentifyFile("").exists);
  std::string bytes = Pattern(1 << 20);
  Write(path, bytes);
  const auto written = fs::last_write_time(path);
  const FileIdentity a = IdentifyFile(path.string());
  ASSERT_TRUE(a.exists);
  EXPECT_EQ(a.size, bytes.size());
  EXPECT_EQ(a.content_hash, Fnv1a64FileEdges(path.string(), bytes.size(), kIdentityEdgeBytes));
  EXPECT_TRUE(IdentifyFile(path.string()) == a);

  ViewIdentity before, now;
  before.depth = a;
  // A byte near the end: the content hash differs.
  bytes[bytes.size() - 10] ^= 1;
  Write(path, bytes);
  now.depth = IdentifyFile(path.string());
  EXPECT_NE(now.depth.content_hash, a.content_hash);
  EXPECT_EQ(DescribeViewChange(before, now), "depth map changed (size 1048576 -> 1048576, content hash differs)");
  // A byte in the middle (outside the sampled edges) with the old mtime restored: the same identity (what the
  // sampled hash cannot see); with a new mtime: changed, and said so.
  bytes[bytes.size() - 10] ^= 1;
  bytes[bytes.size() / 2] ^= 1;
  Write(path, bytes);
  now.depth = IdentifyFile(path.string());
  EXPECT_EQ(now.depth.content_hash, a.content_hash);
  EXPECT_EQ(DescribeViewChange(before, now),
            "depth map changed (size 1048576 -> 1048576, modified time differs; sampled content equal)");
  fs::last_write_time(path, written);
  EXPECT_TRUE(IdentifyFile(path.string()) == a);
  // Size, appearance, disappearance, and the parts a caller asks about.
  Write(path, bytes + "x");
  now.depth = IdentifyFile(path.string());
  EXPECT_EQ(DescribeViewChange(before, now), "depth map changed (size 1048576 -> 1048577, content hash differs)");
  EXPECT_EQ(DescribeViewChange(before, now, kImageInput | kCameraInput), "");
  now.image = a;
  EXPECT_EQ(DescribeViewChange(before, now, kImageInput), "image appeared");
  EXPECT_EQ(DescribeViewChange(now, before, kImageInput), "image is gone");
}

TEST(ViewIdentityTest, CameraHashSeesPoseAndIntrinsics) {
  View view;
  view.name = "a.jpg";
  view.index = 12;
  view.camera = PinholeCamera{640, 480, 500, 500, 320, 240};
  const uint64_t h = CameraHash(view);
  View moved = view;
  moved.cam_from_world.translation.x() += 1e-9;
  EXPECT_NE(CameraHash(moved), h);
  View zoomed = view;
  zoomed.camera.fx += 1e-9;
  EXPECT_NE(CameraHash(zoomed), h);
  ViewIdentity a, b;
  a.camera_hash = h;
  b.camera_hash = CameraHash(moved);
  EXPECT_EQ(DescribeViewChange(a, b), "camera changed (pose or intrinsics)");
  EXPECT_EQ(ViewLabel(view), "view 12 (a.jpg)");
}

// The views a depth map was matched with decide which agreeing maps count as independent support
// (fusion.independent_support): a tile fused before an edit of patch-match.cfg must not count as done after it.
TEST(ViewIdentityTest, PartnersAreAPartOfTheIdentity) {
  View view;
  EXPECT_EQ(PartnersHash(view), 0u);
  view.matching_partners = {3, 5};
  const uint64_t h = PartnersHash(view);
  EXPECT_NE(h, 0u);
  View other = view;
  other.matching_partners = {3, 6};
  EXPECT_NE(PartnersHash(other), h);
  ViewIdentity a, b;
  a.partners_hash = h;
  b.partners_hash = PartnersHash(other);
  EXPECT_EQ(DescribeViewChange(a, b), "stereo partners changed (the views its depth map was matched with)");
  EXPECT_EQ(DescribeViewChange(a, b, kDepthInput | kImageInput | kCameraInput), "");
  // Written only where known, read back either way.
  EXPECT_EQ(ViewIdentityJson(ViewIdentity{}).find("partners"), std::string::npos);
  const auto back = ParseViewIdentityJson(ViewIdentityJson(a));
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->partners_hash, h);
  EXPECT_EQ(DescribeViewChange(a, *back), "");
}

TEST(ViewIdentityTest, JsonRoundTrip) {
  ViewIdentity id;
  id.depth = {true, 307210, 1795610751979742031, 0xfedcba9876543210ull};
  id.camera_hash = 0x0123456789abcdefull;
  const auto back = ParseViewIdentityJson(ViewIdentityJson(id));
  ASSERT_TRUE(back.has_value());
  EXPECT_TRUE(back->depth == id.depth);
  EXPECT_FALSE(back->image.exists);
  EXPECT_EQ(back->camera_hash, id.camera_hash);
  EXPECT_EQ(DescribeViewChange(id, *back), "");
  EXPECT_FALSE(ParseViewIdentityJson("{\"depth\": 1}").has_value());
  EXPECT_FALSE(ParseViewIdentityJson("not json").has_value());
}

// Throughput of FNV-1a as implemented (io/file_checksum.h) on a 64 MiB file in the page cache: the sampled hash
// reads 128 KiB of it; the full hash every byte. Printed for docs/design.md (input identities); asserts only that both ran.
TEST(ViewIdentityTest, HashingThroughput) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "big.bin";
  const std::string bytes = Pattern(64u << 20);
  Write(path, bytes);
  const auto time = [](auto f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  uint64_t full = 0;
  const double full_s = time([&] { full = Fnv1a64File(path.string()); });
  FileIdentity id;
  const double sampled_s = time([&] {
    for (int i = 0; i < 100; ++i) id = IdentifyFile(path.string());
  });
  EXPECT_EQ(full, Fnv1a64(bytes));
  EXPECT_TRUE(id.exists);
  std::printf("hashing: full FNV-1a %.0f MiB/s (64 MiB in %.3f s); identity of a 64 MiB file (stat + 2 x 64 KiB) "
              "%.3f ms\n",
              64.0 / full_s, full_s, sampled_s * 1000.0 / 100);
}

}  // namespace
}  // namespace sacfuse
