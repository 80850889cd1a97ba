#include "io/superpixel_io.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

// A consistent map: 8x8-ish cells (with irregular last row/column) and statistics matching the labels.
SuperpixelMap MakeMap(int width, int height) {
  SuperpixelMap map;
  map.width = width;
  map.height = height;
  const int cells_x = (width + 7) / 8;
  map.clusters.resize(static_cast<size_t>(cells_x) * ((height + 7) / 8));
  std::vector<int32_t> labels(static_cast<size_t>(width) * height);
  std::vector<double> sc(map.clusters.size(), 0), sr(map.clusters.size(), 0);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const int32_t l = (r / 8) * cells_x + c / 8;
      labels[static_cast<size_t>(r) * width + c] = l;
      ++map.clusters[l].pixel_count;
      if ((r + c) % 4 != 0) ++map.clusters[l].valid_count;
      sc[l] += c + 0.5;
      sr[l] += r + 0.5;
    }
  }
  for (size_t i = 0; i < map.clusters.size(); ++i) {
    SuperpixelCluster& cl = map.clusters[i];
    cl.centroid_col = static_cast<float>(sc[i] / cl.pixel_count);
    cl.centroid_row = static_cast<float>(sr[i] / cl.pixel_count);
    cl.depth_m = i % 5 == 0 ? 0.0f : 12.5f + 0.25f * i;
  }
  map.labels = SuperpixelLabels(width, height, labels);
  return map;
}

void ExpectClustersEqual(const std::vector<SuperpixelCluster>& a, const std::vector<SuperpixelCluster>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].centroid_col, b[i].centroid_col) << i;
    EXPECT_EQ(a[i].centroid_row, b[i].centroid_row) << i;
    EXPECT_EQ(a[i].depth_m, b[i].depth_m) << i;
    EXPECT_EQ(a[i].pixel_count, b[i].pixel_count) << i;
    EXPECT_EQ(a[i].valid_count, b[i].valid_count) << i;
  }
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void Spit(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Expects every reader to throw InputError naming `path`.
void ExpectAllReadersReject(const std::string& path, const std::string& why) {
  SCOPED_TRACE(why);
  const auto check = [&](const auto& read) {
    try {
      read();
      ADD_FAILURE() << "expected InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  };
  check([&] { ReadSuperpixels(path); });
  check([&] { ReadSuperpixelRows(path, 0, 1); });
}

TEST(SuperpixelIoTest, RoundTripFullAndRowWindows) {
  testing::TempDir dir;
  const std::string path = (dir / "sub" / "view_0007.spx").string();
  const SuperpixelMap map = MakeMap(37, 150);  // three bands of 64 rows: non-zero band bases
  WriteSuperpixels(path, map, 0x0123456789abcdefull);

  const SuperpixelFileInfo info = ReadSuperpixelInfo(path);
  EXPECT_EQ(info.width, 37);
  EXPECT_EQ(info.height, 150);
  EXPECT_EQ(info.num_clusters, map.clusters.size());
  EXPECT_EQ(info.options_hash, 0x0123456789abcdefull);
  // The banded layout: 3 band bases, u16 labels.
  EXPECT_EQ(std::filesystem::file_size(path), 32u + 3u * 4u + 37u * 150u * 2u + map.clusters.size() * 20u);

  const SuperpixelMap full = ReadSuperpixels(path);
  EXPECT_EQ(full.width, map.width);
  EXPECT_EQ(full.height, map.height);
  EXPECT_EQ(full.labels, map.labels);
  ExpectClustersEqual(full.clusters, map.clusters);

  const std::vector<std::pair<int, int>> windows = {{0, 150}, {5, 17}, {60, 70}, {63, 129}, {149, 150}, {0, 1}, {11, 11}};
  for (const auto& window : windows) {
    SCOPED_TRACE(std::to_string(window.first) + ".." + std::to_string(window.second));
    const SuperpixelMap rows = ReadSuperpixelRows(path, window.first, window.second);
    EXPECT_EQ(rows.width, 37);
    EXPECT_EQ(rows.height, window.second - window.first);
    const std::vector<int32_t> all = map.labels.ToVector();
    const std::vector<int32_t> slice(all.begin() + window.first * 37, all.begin() + window.second * 37);
    EXPECT_EQ(rows.labels.ToVector(), slice);
    ExpectClustersEqual(rows.clusters, map.clusters);
  }
  EXPECT_THROW(ReadSuperpixelRows(path, 5, 151), Error);
  EXPECT_THROW(ReadSuperpixelRows(path, -1, 3), Error);
  EXPECT_THROW(ReadSuperpixelRows(path, 6, 5), Error);

  // No temporary files left behind; rewriting replaces the file.
  WriteSuperpixels(path, MakeMap(9, 9), 7);
  EXPECT_EQ(ReadSuperpixelInfo(path).width, 9);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir / "sub"), std::filesystem::directory_iterator()), 1);
}

TEST(SuperpixelIoTest, UnpackedLabelsWriteTheSameFile) {
  // The tiled runs' superpixel pass writes maps whose labels are not packed (SuperpixelLabels::Unpacked): the file
  // must be the packed map's, in the banded layout (three bands of 64 rows) and in the int32 one (a band whose
  // labels span more than a u16).
  testing::TempDir dir;
  SuperpixelMap wide;
  wide.width = 2;
  wide.height = 1;
  wide.clusters.resize(65538);
  wide.labels = SuperpixelLabels(2, 1, {0, 65537});
  ASSERT_FALSE(wide.labels.banded());
  for (const SuperpixelMap& packed : {MakeMap(37, 150), MakeMap(203, 157), wide}) {
    SCOPED_TRACE(std::to_string(packed.width) + "x" + std::to_string(packed.height));
    SuperpixelMap unpacked = packed;
    unpacked.labels = SuperpixelLabels::Unpacked(packed.width, packed.height, packed.labels.ToVector());
    const std::string a = (dir / "packed.spx").string(), b = (dir / "unpacked.spx").string();
    WriteSuperpixels(a, packed, 11);
    WriteSuperpixels(b, unpacked, 11);
    EXPECT_EQ(Slurp(a), Slurp(b));
    EXPECT_EQ(Slurp(b).substr(0, 8), packed.labels.banded() ? "SACSPX02" : "SACSPX01");
  }
}

TEST(SuperpixelIoTest, LabelWindowsAreTheCropOfTheFullMap) {
  testing::TempDir dir;
  const std::string path = (dir / "w.spx").string();
  const SuperpixelMap map = MakeMap(37, 150);
  WriteSuperpixels(path, map, 5);
  ExpectClustersEqual(ReadSuperpixelClusters(path), map.clusters);
  for (const PixelWindow& w : {PixelWindow{0, 150, 0, 37}, PixelWindow{3, 17, 5, 6}, PixelWindow{149, 150, 30, 37},
                               PixelWindow{10, 20, 0, 12}, PixelWindow{60, 130, 7, 20}}) {
    SCOPED_TRACE(PixelWindowText(w));
    SuperpixelFileInfo info;
    const std::vector<int32_t> labels = ReadSuperpixelLabelWindow(path, w, &info);
    EXPECT_EQ(info.width, 37);
    EXPECT_EQ(info.num_clusters, map.clusters.size());
    ASSERT_EQ(labels.size(), w.num_pixels());
    for (int r = 0; r < w.height(); ++r) {
      for (int c = 0; c < w.width(); ++c) {
        EXPECT_EQ(labels[r * w.width() + c], map.label(w.row_begin + r, w.col_begin + c));
      }
    }
  }
  EXPECT_THROW(ReadSuperpixelLabelWindow(path, PixelWindow{0, 151, 0, 5}), Error);
  EXPECT_THROW(ReadSuperpixelLabelWindow(path, PixelWindow{0, 5, 30, 38}), Error);
  EXPECT_THROW(ReadSuperpixelLabelWindow(path, PixelWindow{4, 4, 0, 5}), Error);
  // The partial readers check what they read; a truncated file fails the header's size check for both.
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 3);
  EXPECT_THROW(ReadSuperpixelLabelWindow(path, PixelWindow{0, 1, 0, 1}), InputError);
  EXPECT_THROW(ReadSuperpixelClusters(path), InputError);
}

TEST(SuperpixelIoTest, OnDiskLayoutIsLittleEndian) {
  testing::TempDir dir;
  const std::string path = (dir / "a.spx").string();
  SuperpixelMap map = MakeMap(16, 72);  // two bands (rows 0-63: labels 0-15, rows 64-71: labels 16-17)
  WriteSuperpixels(path, map, 0x1122334455667788ull);
  const std::string bytes = Slurp(path);
  const size_t labels = 32 + 2 * 4, table = labels + 16 * 72 * 2;
  ASSERT_EQ(bytes.size(), table + 18 * 20);
  EXPECT_EQ(bytes.substr(0, 8), "SACSPX02");
  EXPECT_EQ(bytes.substr(8, 4), std::string("\x10\0\0\0", 4));
  EXPECT_EQ(bytes.substr(12, 4), std::string("\x48\0\0\0", 4));
  EXPECT_EQ(bytes.substr(16, 8), std::string("\x12\0\0\0\0\0\0\0", 8));
  EXPECT_EQ(bytes.substr(24, 8), std::string("\x88\x77\x66\x55\x44\x33\x22\x11", 8));
  EXPECT_EQ(bytes.substr(32, 8), std::string("\0\0\0\0\x10\0\0\0", 8));  // band bases 0 and 16
  EXPECT_EQ(bytes.substr(labels + 8 * 2, 2), std::string("\x01\0", 2));  // row 0, col 8 -> cluster 1
  EXPECT_EQ(bytes.substr(labels + (64 * 16 + 8) * 2, 2), std::string("\x01\0", 2));  // row 64, col 8 -> 16 + 1
  EXPECT_EQ(bytes.substr(table + 20 + 12, 4), std::string("\x40\0\0\0", 4));  // cluster 1: 64 pixels
}

// A band spanning more than 65,535 labels does not fit u16 offsets: the int32 layout (SACSPX01), read as before.
TEST(SuperpixelIoTest, MapsWhoseBandsSpanTooManyLabelsUseInt32Labels) {
  testing::TempDir dir;
  const std::string path = (dir / "wide.spx").string();
  SuperpixelMap map;
  map.width = 70000;
  map.height = 1;
  std::vector<int32_t> labels;
  for (int c = 0; c < map.width; ++c) {
    labels.push_back(c);
    SuperpixelCluster cluster;
    cluster.centroid_col = c + 0.5f;
    cluster.centroid_row = 0.5f;
    cluster.depth_m = 10.0f;
    cluster.pixel_count = 1;
    cluster.valid_count = 1;
    map.clusters.push_back(cluster);
  }
  map.labels = SuperpixelLabels(map.width, map.height, labels);
  EXPECT_FALSE(map.labels.banded());
  WriteSuperpixels(path, map, 9);
  const std::string bytes = Slurp(path);
  EXPECT_EQ(bytes.substr(0, 8), "SACSPX01");
  ASSERT_EQ(bytes.size(), 32u + 70000u * 4u + 70000u * 20u);
  EXPECT_EQ(bytes.substr(32 + 66000 * 4, 4), std::string("\xd0\x01\x01\0", 4));  // 66000 = 0x101d0
  const SuperpixelMap back = ReadSuperpixels(path);
  EXPECT_EQ(back.labels, map.labels);
  EXPECT_EQ(ReadSuperpixelLabelWindow(path, PixelWindow{0, 1, 65999, 66002}),
            (std::vector<int32_t>{65999, 66000, 66001}));
}

TEST(SuperpixelIoTest, EmptyMapRoundTrips) {
  testing::TempDir dir;
  const std::string path = (dir / "empty.spx").string();
  WriteSuperpixels(path, SuperpixelMap{}, 1);
  const SuperpixelMap map = ReadSuperpixels(path);
  EXPECT_EQ(map.width, 0);
  EXPECT_TRUE(map.labels.empty());
  EXPECT_TRUE(map.clusters.empty());
}

TEST(SuperpixelIoTest, CorruptOrTruncatedFilesAreRejectedNamingTheFile) {
  testing::TempDir dir;
  const std::string good_path = (dir / "good.spx").string();
  WriteSuperpixels(good_path, MakeMap(24, 20), 3);
  const std::string good = Slurp(good_path);
  const std::string path = (dir / "bad.spx").string();
  const size_t labels = 32 + 4;  // one band base
  const size_t table = labels + 24 * 20 * 2;

  ExpectAllReadersReject((dir / "missing.spx").string(), "missing file");

  std::string bytes = good;
  bytes[3] = 'X';
  Spit(path, bytes);
  ExpectAllReadersReject(path, "bad magic");
  EXPECT_THROW(ReadSuperpixelInfo(path), InputError);

  Spit(path, good.substr(0, good.size() - 1));
  ExpectAllReadersReject(path, "truncated by one byte");
  EXPECT_THROW(ReadSuperpixelInfo(path), InputError);

  Spit(path, good.substr(0, 20));
  ExpectAllReadersReject(path, "truncated header");

  Spit(path, good + "x");
  ExpectAllReadersReject(path, "trailing garbage");

  bytes = good;
  bytes[8] = '\xff';  // width 255 + ... : sizes no longer match the length
  Spit(path, bytes);
  ExpectAllReadersReject(path, "wrong width");

  bytes = good;
  bytes[16] = '\0';  // zero clusters for a non-empty raster (length checked first: fix it up by hand)
  bytes.resize(table);
  Spit(path, bytes);
  ExpectAllReadersReject(path, "no clusters");

  bytes = good;
  bytes[labels + 2 * 3] = '\x7f';  // row 0, col 3: label 127 > number of clusters
  Spit(path, bytes);
  ExpectAllReadersReject(path, "label out of range");
  EXPECT_NO_THROW(ReadSuperpixelRows(path, 1, 20)) << "only the rows read are range-checked";

  bytes = good;
  bytes[labels + 2 * 3] = '\x01';  // row 0, col 3 moved to cluster 1: table counts disagree with the labels
  Spit(path, bytes);
  EXPECT_THROW(ReadSuperpixels(path), InputError);

  bytes = good;
  bytes[table + 12] = '\x05';  // cluster 0 pixel count: sum no longer matches the raster
  Spit(path, bytes);
  ExpectAllReadersReject(path, "pixel counts");

  bytes = good;
  bytes.replace(table + 8, 4, std::string("\x00\x00\xc0\x7f", 4));  // cluster 0 depth NaN
  Spit(path, bytes);
  ExpectAllReadersReject(path, "NaN depth");

  bytes = good;
  bytes[32] = '\x7f';  // band base 127 > number of clusters
  Spit(path, bytes);
  ExpectAllReadersReject(path, "band base out of range");
}

TEST(SuperpixelIoTest, InconsistentMapsAreNotWritten) {
  testing::TempDir dir;
  const std::string path = (dir / "x.spx").string();
  SuperpixelMap map = MakeMap(10, 10);
  std::vector<int32_t> labels = map.labels.ToVector();
  labels[5] = static_cast<int32_t>(map.clusters.size());
  map.labels = SuperpixelLabels(10, 10, labels);
  EXPECT_THROW(WriteSuperpixels(path, map, 0), Error);
  map = MakeMap(10, 10);
  labels.resize(90);
  map.labels = SuperpixelLabels(10, 9, labels);  // one row short
  EXPECT_THROW(WriteSuperpixels(path, map, 0), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace sacfuse
