// MergeTileLas: the tiles ahead are made ready on the thread pool while the writer appends earlier ones in grid
// order, so the merged LAZ is byte for byte the file of a tile-by-tile merge (LasWriter::AppendLaz, one tile after
// another) for any thread count; a bad tile fails the merge naming the first bad one in grid order, with no output.
#include "tiles/tile_merge.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "io/las_format.h"
#include "io/las_reader.h"
#include "io/las_writer.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
namespace lf = las_format;
using testing::TempDir;

const Eigen::Vector3d kOffset(391000, 5706000, 0);

LasWriterOptions TileOptions() {
  LasWriterOptions o;
  o.compressed = true;
  o.offset = kOffset;
  return o;
}

// Fused-like points (PDRF 7): coordinates, colour, source ID.
void WriteTile(const fs::path& path, size_t n, uint32_t seed, const LasWriterOptions& options = TileOptions()) {
  std::mt19937 rng(seed);
  std::vector<LasPoint> pts(n);
  for (size_t i = 0; i < n; ++i) {
    pts[i].xyz = {391234.5 + 0.001 * (rng() % 100000), 5706543.2 + 0.001 * (rng() % 100000), 80 + 0.001 * (rng() % 9999)};
    pts[i].rgb = {static_cast<uint16_t>(rng()), static_cast<uint16_t>(rng()), static_cast<uint16_t>(rng())};
    pts[i].point_source_id = static_cast<uint16_t>(1 + i / 4000);
  }
  LasWriter w(path.string(), options);
  w.WritePoints(pts.data(), pts.size());
  w.Close();
}

// The file's bytes with the header's creation day and year zeroed.
std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (size_t k = lf::kOffCreationDay; k < lf::kOffCreationDay + 4 && k < bytes.size(); ++k) bytes[k] = 0;
  return bytes;
}

TEST(TileMergeTest, MergedLazIsTheTileByTileFileForAnyThreadCount) {
  TempDir dir;
  // Full chunks and a last one, tails only, exactly one full chunk: more tail points than one chunk gather.
  const std::vector<size_t> sizes = {61000, 777, 23000, 50000, 104321, 9000, 31000};
  std::vector<std::string> tiles;
  for (size_t i = 0; i < sizes.size(); ++i) {
    tiles.push_back((dir.path() / ("tile" + std::to_string(i) + ".laz")).string());
    WriteTile(tiles.back(), sizes[i], static_cast<uint32_t>(7 + i));
  }
  {
    LasWriter w((dir.path() / "one_by_one.laz").string(), TileOptions());
    for (const std::string& tile : tiles) {
      LasReader reader(tile);
      ASSERT_TRUE(w.AppendLaz(reader));
    }
    w.Close();
  }
  const std::string expected = Bytes(dir.path() / "one_by_one.laz");
  CloudFileOptions cloud;
  cloud.las = TileOptions();
  for (const int threads : {1, 2, 4}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    const fs::path out = dir.path() / ("merged" + std::to_string(threads) + ".laz");
    size_t last_done = 0;
    EXPECT_EQ(MergeTileLas(tiles, out.string(), cloud, [&](size_t done, size_t total) {
                EXPECT_EQ(done, last_done + 1);  // in order, once per tile
                EXPECT_EQ(total, tiles.size());
                last_done = done;
              }),
              279098u);
    EXPECT_EQ(last_done, tiles.size());
    EXPECT_TRUE(Bytes(out) == expected) << threads << " threads";
  }
  // LAS output: every point decoded and written, in grid order.
  cloud.las.compressed = false;
  const fs::path las = dir.path() / "merged.las";
  EXPECT_EQ(MergeTileLas(tiles, las.string(), cloud), 279098u);
  std::vector<LasPoint> in_order;
  for (const std::string& tile : tiles) {
    const std::vector<LasPoint> pts = ReadAllLasPoints(tile);
    in_order.insert(in_order.end(), pts.begin(), pts.end());
  }
  const std::vector<LasPoint> merged = ReadAllLasPoints(las.string());
  ASSERT_EQ(merged.size(), in_order.size());
  for (size_t i = 0; i < merged.size(); i += 997) EXPECT_EQ(merged[i].xyz, in_order[i].xyz) << i;
}

TEST(TileMergeTest, TheFirstBadTileInGridOrderFailsTheMergeWithNoOutput) {
  TempDir dir;
  std::vector<std::string> tiles;
  for (size_t i = 0; i < 6; ++i) tiles.push_back((dir.path() / ("tile" + std::to_string(i) + ".laz")).string());
  LasWriterOptions shifted = TileOptions();
  shifted.offset = Eigen::Vector3d(391000, 5706000, 100);
  for (size_t i : {0, 1, 3, 5}) WriteTile(tiles[i], 3000, static_cast<uint32_t>(i));
  WriteTile(tiles[2], 3000, 2, shifted);  // another offset
  // tiles[4] missing
  CloudFileOptions cloud;
  cloud.las = TileOptions();
  for (const int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    const fs::path out = dir.path() / "merged.laz";
    try {
      MergeTileLas(tiles, out.string(), cloud);
      ADD_FAILURE() << "the merge accepted a tile of another offset";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), tiles[2]) << e.what();
      EXPECT_NE(std::string(e.what()).find("scale/offset differ"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
    const auto files = std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator());
    EXPECT_EQ(static_cast<size_t>(files), tiles.size() - 1) << "a temporary file was left";
  }
}

}  // namespace
}  // namespace sacfuse
