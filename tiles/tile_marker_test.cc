#include "tiles/tile_marker.h"

#include "io/atomic_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "io/las_writer.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

class TileMarkerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    LasWriterOptions options;
    options.offset = Eigen::Vector3d(1000, 2000, 0);
    LasWriter writer(Las(), options);
    std::vector<FusedPoint> points(100);
    for (size_t i = 0; i < points.size(); ++i) {
      points[i].point_in_world = Eigen::Vector3d(1001 + 0.1 * i, 2002, 50 + 0.01 * i);
      points[i].view_index = static_cast<uint32_t>(i % 3);
    }
    writer.Write(points.data(), points.size());
    writer.Close();
    TileDoneMarker marker = DescribeTileFile(Dir(), "3_4", TileCloudFileName("3_4", false));
    marker.config_hash = "hash-a";
    marker.views = 3;
    marker.points_per_view = kPointsPerView;
    WriteTileDoneMarker(Dir(), marker);
  }
  // Of the 100 points above: view index i % 3.
  const std::vector<std::pair<uint32_t, uint64_t>> kPointsPerView = {{0, 34}, {1, 33}, {2, 33}};
  std::string Dir() const { return dir_.path().string(); }
  std::string Las() const { return (dir_ / "3_4.laz").string(); }

  TempDir dir_;
};

TEST_F(TileMarkerTest, CompleteTileIsDoneAndMarkerRoundTrips) {
  EXPECT_TRUE(VerifyTileDone(Dir(), "3_4", "hash-a").done) << VerifyTileDone(Dir(), "3_4", "hash-a").reason;
  const auto marker = ReadTileDoneMarker(Dir(), "3_4");
  ASSERT_TRUE(marker);
  EXPECT_EQ(marker->points, 100u);
  EXPECT_EQ(marker->file, "3_4.laz");
  EXPECT_EQ(TileCloudPath(Dir(), *marker), Las());
  EXPECT_EQ(marker->file_size, fs::file_size(Las()));
  EXPECT_EQ(marker->checksum.size(), 16u);
  EXPECT_NEAR(marker->min[0], 1001.0, 1e-9);
  EXPECT_NEAR(marker->max[0], 1010.9, 1e-9);
  EXPECT_GT(marker->finished_unix_ns, 0);
  EXPECT_EQ(marker->points_per_view, kPointsPerView);
}

// The merge takes the points per view from the marker: a marker without them (an older sacfuse) or whose
// counts do not add up to its points is not done.
TEST_F(TileMarkerTest, PointsPerViewMustAddUpToThePoints) {
  TileDoneMarker marker = *ReadTileDoneMarker(Dir(), "3_4");
  for (const auto& per_view : {std::vector<std::pair<uint32_t, uint64_t>>{},
                               std::vector<std::pair<uint32_t, uint64_t>>{{0, 34}, {1, 33}, {2, 32}}}) {
    marker.points_per_view = per_view;
    WriteTileDoneMarker(Dir(), marker);
    const TileCheck check = VerifyTileDone(Dir(), "3_4", "hash-a");
    EXPECT_FALSE(check.done);
    EXPECT_NE(check.reason.find("points per view add up to"), std::string::npos) << check.reason;
  }
}

// The marker names the tile's point file: a COPC tile (<id>.copc.laz) is checked as such, and a marker of a version
// before COPC tiles (no "file") names <id>.laz.
TEST_F(TileMarkerTest, MarkerNamesItsPointFile) {
  EXPECT_EQ(TileCloudFileName("3_4", true), "3_4.copc.laz");
  fs::rename(Las(), dir_ / "3_4.copc.laz");
  TileDoneMarker marker = *ReadTileDoneMarker(Dir(), "3_4");
  EXPECT_FALSE(VerifyTileDone(Dir(), "3_4", "hash-a").done);  // names 3_4.laz, which is gone
  marker.file = "3_4.copc.laz";
  WriteTileDoneMarker(Dir(), marker);
  EXPECT_TRUE(VerifyTileDone(Dir(), "3_4", "hash-a").done);
  marker.file.clear();  // as written by older versions
  WriteTileDoneMarker(Dir(), marker);
  EXPECT_EQ(TileCloudPath(Dir(), *ReadTileDoneMarker(Dir(), "3_4")), Las());
  EXPECT_FALSE(VerifyTileDone(Dir(), "3_4", "hash-a").done);
  ClearTileState(Dir(), "3_4");
  EXPECT_FALSE(fs::exists(dir_ / "3_4.copc.laz"));
}

TEST_F(TileMarkerTest, WrongConfigHashIsNotDone) {
  const TileCheck check = VerifyTileDone(Dir(), "3_4", "hash-b");
  EXPECT_FALSE(check.done);
  EXPECT_NE(check.reason.find("another config"), std::string::npos) << check.reason;
}

TEST_F(TileMarkerTest, TruncatedOrExtendedLasIsNotDone) {
  fs::resize_file(Las(), fs::file_size(Las()) - 10);
  EXPECT_FALSE(VerifyTileDone(Dir(), "3_4", "hash-a").done);
  fs::resize_file(Las(), fs::file_size(Las()) + 20);
  const TileCheck check = VerifyTileDone(Dir(), "3_4", "hash-a");
  EXPECT_FALSE(check.done);
  EXPECT_NE(check.reason.find("size"), std::string::npos) << check.reason;
}

TEST_F(TileMarkerTest, FlippedByteFailsTheChecksumButNotTheQuickCheck) {
  {
    std::fstream f(Las(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(Las()) - 5));
    f.put('\x7f');
  }
  const TileCheck check = VerifyTileDone(Dir(), "3_4", "hash-a");
  EXPECT_FALSE(check.done);
  EXPECT_NE(check.reason.find("checksum"), std::string::npos) << check.reason;
  EXPECT_TRUE(VerifyTileDone(Dir(), "3_4", "hash-a", /*full_checksum=*/false).done);
}

TEST_F(TileMarkerTest, MissingLasOrBrokenMarkerIsNotDone) {
  fs::remove(Las());
  EXPECT_FALSE(VerifyTileDone(Dir(), "3_4", "hash-a").done);
  std::ofstream(TileDonePath(Dir(), "3_4")) << "{\"id\": \"3_4\", \"poi";
  EXPECT_FALSE(VerifyTileDone(Dir(), "3_4", "hash-a").done);
  fs::remove(TileDonePath(Dir(), "3_4"));
  EXPECT_EQ(VerifyTileDone(Dir(), "3_4", "hash-a").reason, "no done marker");
}

TEST_F(TileMarkerTest, EmptyTileIsDoneWithoutLasButNotWithAStrayOne) {
  TileDoneMarker empty = DescribeTileFile(Dir(), "0_0", "");
  empty.config_hash = "hash-a";
  WriteTileDoneMarker(Dir(), empty);
  EXPECT_TRUE(VerifyTileDone(Dir(), "0_0", "hash-a").done);
  fs::copy_file(Las(), dir_ / "0_0.laz");
  EXPECT_FALSE(VerifyTileDone(Dir(), "0_0", "hash-a").done);
}

TEST_F(TileMarkerTest, FailedMarkerAndClearingAndTemporaryFiles) {
  WriteTileFailedMarker(Dir(), "3_4", "depth map unreadable");
  EXPECT_EQ(ReadTileFailedReason(Dir(), "3_4").value_or(""), "depth map unreadable");
  std::ofstream(dir_ / "3_4.las") << "tile of a version before LAZ tiles";
  ClearTileState(Dir(), "3_4");
  EXPECT_FALSE(fs::exists(Las()));
  EXPECT_FALSE(fs::exists(dir_ / "3_4.las"));
  EXPECT_EQ(TileCloudFileName("3_4", false), "3_4.laz");
  EXPECT_FALSE(ReadTileFailedReason(Dir(), "3_4"));
  EXPECT_FALSE(VerifyTileDone(Dir(), "3_4", "hash-a").done);
  std::ofstream(Las() + ".tmp-123-0") << "partial";
  std::ofstream(dir_ / "keep.las") << "x";
  std::ofstream(dir_ / "notes.tmp-draft") << "not ours";  // not the TemporaryPathFor pattern: kept
  // A work folder named like a temporary file (a COPC build's, io/copc_writer.h) goes with its contents.
  fs::create_directories(dir_ / "fused.copc.laz.tmp-123-1");
  std::ofstream(dir_ / "fused.copc.laz.tmp-123-1" / "spill.las") << "spilled points";
  const auto any_owner = [](const TemporaryFileOwner&) { return true; };  // io/atomic_file_test has the rules
  std::vector<std::string> removed = RemoveTemporaryFiles(Dir(), false, any_owner);
  std::sort(removed.begin(), removed.end());
  EXPECT_EQ(removed, (std::vector<std::string>{Las() + ".tmp-123-0", (dir_ / "fused.copc.laz.tmp-123-1").string()}));
  EXPECT_FALSE(fs::exists(dir_ / "fused.copc.laz.tmp-123-1"));
  EXPECT_TRUE(fs::exists(dir_ / "keep.las"));
  EXPECT_TRUE(fs::exists(dir_ / "notes.tmp-draft"));
}

}  // namespace
}  // namespace sacfuse
