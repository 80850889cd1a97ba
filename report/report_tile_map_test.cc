// The tile map: status and time colours per tile, ids, placement, the untiled extent.
#include "report/report_tile_map.h"

#include <regex>

#include <gtest/gtest.h>

#include "report/report_text.h"

namespace sacfuse {
namespace {

ReportTile Tile(int ix, int iy, TileStatus status, double seconds) {
  ReportTile t;
  t.id = std::to_string(ix) + "_" + std::to_string(iy);
  t.ix = ix;
  t.iy = iy;
  t.has_core = true;
  t.core.min = {100.0 + 20 * ix, 500.0 + 20 * iy};
  t.core.max = {120.0 + 20 * ix, 520.0 + 20 * iy};
  t.status = status;
  t.seconds = seconds;
  t.points = 1000;
  return t;
}

// The fill of the rectangle of the tile whose <title> starts with "tile ID:".
std::string FillOf(const std::string& svg, const std::string& id) {
  const std::regex re("<title>tile " + id + ":[^<]*</title><rect [^>]*fill='(#[0-9a-f]{6})'");
  std::smatch m;
  return std::regex_search(svg, m, re) ? m[1].str() : "";
}

std::string Hex(const Rgb& c) { return HexColour(c[0], c[1], c[2]); }

TEST(ReportTileMapTest, StatusMapColoursEachTileByItsStatus) {
  const std::vector<ReportTile> tiles = {Tile(0, 0, TileStatus::kDone, 3), Tile(1, 0, TileStatus::kFailed, 0),
                                         Tile(0, 1, TileStatus::kPending, 0)};
  const std::string svg = TileMapSvg(tiles, TileColouring::kStatus, 400, 400);
  EXPECT_EQ(FillOf(svg, "0_0"), Hex(TileStatusColour(TileStatus::kDone)));
  EXPECT_EQ(FillOf(svg, "1_0"), Hex(TileStatusColour(TileStatus::kFailed)));
  EXPECT_EQ(FillOf(svg, "0_1"), Hex(TileStatusColour(TileStatus::kPending)));
  for (const char* id : {">0_0<", ">1_0<", ">0_1<"}) EXPECT_NE(svg.find(id), std::string::npos) << id;
  EXPECT_NE(svg.find("done (1)"), std::string::npos);
  EXPECT_NE(svg.find("failed (1)"), std::string::npos);
  EXPECT_NE(TileStatusColour(TileStatus::kDone), TileStatusColour(TileStatus::kFailed));
}

TEST(ReportTileMapTest, NorthIsUp) {
  const std::vector<ReportTile> tiles = {Tile(0, 0, TileStatus::kDone, 1), Tile(0, 1, TileStatus::kDone, 1)};
  const std::string svg = TileMapSvg(tiles, TileColouring::kStatus, 400, 400);
  const auto y_of = [&](const std::string& id) {
    std::smatch m;
    const std::regex re("<title>tile " + id + ":[^<]*</title><rect x='[^']*' y='([^']*)'");
    EXPECT_TRUE(std::regex_search(svg, m, re)) << id;
    return std::stod(m[1].str());
  };
  EXPECT_LT(y_of("0_1"), y_of("0_0"));  // the northern tile is drawn higher
}

TEST(ReportTileMapTest, TimeMapRampsFromFastToSlowAndGreysUnfinishedTiles) {
  const std::vector<ReportTile> tiles = {Tile(0, 0, TileStatus::kDone, 2), Tile(1, 0, TileStatus::kDone, 10),
                                         Tile(2, 0, TileStatus::kPending, 0)};
  const std::string svg = TileMapSvg(tiles, TileColouring::kTime, 400, 400);
  EXPECT_EQ(FillOf(svg, "0_0"), Hex(TimeRampColour(0, 0, 1)));
  EXPECT_EQ(FillOf(svg, "1_0"), Hex(TimeRampColour(1, 0, 1)));
  EXPECT_EQ(FillOf(svg, "2_0"), Hex(TileStatusColour(TileStatus::kPending)));
  // The ramp darkens with time.
  const Rgb fast = TimeRampColour(0, 0, 1), slow = TimeRampColour(1, 0, 1);
  EXPECT_GT(fast[0] + fast[1] + fast[2], slow[0] + slow[1] + slow[2]);
}

TEST(ReportTileMapTest, UntiledShowsOneExtent) {
  Box2d b;
  b.min = {0, 0};
  b.max = {130, 65};
  const std::string svg = UntiledExtentSvg(b, 360, 260);
  EXPECT_NE(svg.find(">untiled<"), std::string::npos);
  EXPECT_NE(svg.find("130.0 m × 65.0 m"), std::string::npos);
  EXPECT_NE(UntiledExtentSvg(Box2d{}, 360, 260).find("untiled"), std::string::npos);
}

}  // namespace
}  // namespace sacfuse
