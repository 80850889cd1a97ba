#include "tiling/tile_grid.h"

#include <cmath>
#include <iomanip>

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

Box2d Area(double x0, double y0, double x1, double y1) {
  Box2d b;
  b.Extend(Eigen::Vector2d(x0, y0));
  b.Extend(Eigen::Vector2d(x1, y1));
  return b;
}

int CoresContaining(const TileGrid& grid, double x, double y) {
  int n = 0;
  for (const TileIndex& t : grid.Tiles()) n += grid.CoreContains(t, x, y) ? 1 : 0;
  return n;
}

TEST(TileGridTest, AlignedToMultiplesOfTheTileSize) {
  const TileGrid grid(Area(390013.2, 5705007.5, 390061.0, 5705040.0), 20.0, 5.0);
  EXPECT_EQ(grid.num_x(), 4);  // 390000, 390020, 390040, 390060 (390061 lies in the fourth column)
  EXPECT_EQ(grid.num_y(), 3);  // 5705000, 5705020, 5705040 (5705040 itself belongs to the third row)
  const Box2d core = grid.CoreBounds({0, 0});
  EXPECT_DOUBLE_EQ(core.min.x(), 390000.0);
  EXPECT_DOUBLE_EQ(core.max.x(), 390020.0);
  EXPECT_DOUBLE_EQ(core.min.y(), 5705000.0);
  const Box2d halo = grid.HaloBounds({1, 2});
  EXPECT_DOUBLE_EQ(halo.min.x(), 390015.0);
  EXPECT_DOUBLE_EQ(halo.max.x(), 390045.0);
  EXPECT_DOUBLE_EQ(halo.min.y(), 5705035.0);
  EXPECT_DOUBLE_EQ(halo.max.y(), 5705065.0);
}

TEST(TileGridTest, LastColumnHoldsTheAreaMaximum) {
  const TileGrid grid(Area(390013.2, 5705007.5, 390061.0, 5705040.0), 20.0, 5.0);
  // 390061 lies in [390060, 390080): a 4th column.
  EXPECT_EQ(grid.num_x(), 4);
  EXPECT_EQ(grid.TileOf(390061.0, 5705040.0), (TileIndex{3, 2}));
}

TEST(TileGridTest, EveryPointBelongsToExactlyOneCoreAtBorders) {
  const TileGrid grid(Area(390000.0, 5705000.0, 390079.9, 5705059.9), 20.0, 5.0);
  ASSERT_EQ(grid.num_x(), 4);
  ASSERT_EQ(grid.num_y(), 3);
  const double eps[] = {-1e-9, -1e-10, 0.0, 1e-10, 1e-9};
  for (double bx : {390000.0, 390020.0, 390040.0, 390060.0}) {
    for (double by : {5705000.0, 5705020.0, 5705040.0}) {
      for (double ex : eps) {
        for (double ey : eps) {
          const double x = bx + ex, y = by + ey;
          if (x < 390000.0 || y < 5705000.0) continue;  // outside the grid
          EXPECT_EQ(CoresContaining(grid, x, y), 1) << std::setprecision(17) << x << " " << y;
          EXPECT_TRUE(grid.CoreContains(grid.TileOf(x, y), x, y)) << std::setprecision(17) << x << " " << y;
        }
      }
    }
  }
  // Neighbouring doubles around a border fall on either side of it.
  const double border = 390020.0;
  EXPECT_EQ(grid.TileOf(border, 5705001.0), (TileIndex{1, 0}));
  EXPECT_EQ(grid.TileOf(std::nextafter(border, 0.0), 5705001.0), (TileIndex{0, 0}));
}

TEST(TileGridTest, PointsBeyondTheGridGoToTheNearestBorderTile) {
  const TileGrid grid(Area(0.0, 0.0, 39.0, 39.0), 20.0, 5.0);
  EXPECT_EQ(grid.TileOf(-3.0, 50.0), (TileIndex{0, 1}));
  EXPECT_EQ(grid.TileOf(100.0, -1.0), (TileIndex{1, 0}));
}

TEST(TileGridTest, OwnedRegionOfATileHoldsExactlyThePointsTileOfGivesIt) {
  const TileGrid grid(Area(390000.0, 5705000.0, 390079.9, 5705059.9), 20.0, 5.0);
  const double eps[] = {-1e-9, 0.0, 1e-9};
  std::vector<double> xs = {389000.0, 390079.9, 391000.0}, ys = {5704000.0, 5705059.9, 5706000.0};
  for (double bx : {390000.0, 390020.0, 390040.0, 390060.0, 390080.0}) {
    for (double e : eps) xs.push_back(bx + e);
  }
  for (double by : {5705000.0, 5705020.0, 5705040.0, 5705060.0}) {
    for (double e : eps) ys.push_back(by + e);
  }
  for (const TileIndex& t : grid.Tiles()) {
    const OwnedRegion region = grid.OwnedRegionOf(t);
    for (double x : xs) {
      for (double y : ys) {
        EXPECT_EQ(region.Contains({x, y, 100.0}), grid.TileOf(x, y) == t)
            << TileGrid::Id(t) << " " << std::setprecision(17) << x << " " << y;
      }
    }
  }
  EXPECT_FALSE(grid.OwnedRegionOf({1, 1}).OwnsEverything());
  EXPECT_TRUE(TileGrid(Area(0.0, 0.0, 9.0, 9.0), 0.0, 5.0).OwnedRegionOf({0, 0}).OwnsEverything());
}

TEST(TileGridTest, ZeroSizeIsOneTileCoveringEverything) {
  const Box2d area = Area(390013.2, 5705007.5, 390061.0, 5705040.0);
  const TileGrid grid(area, 0.0, 5.0);
  ASSERT_EQ(grid.size(), 1u);
  EXPECT_EQ(TileGrid::Id(grid.Tiles()[0]), "0_0");
  EXPECT_TRUE(grid.CoreContains({0, 0}, 1e6, -1e6));
  EXPECT_DOUBLE_EQ(grid.CoreBounds({0, 0}).min.x(), area.min.x());
}

TEST(TileGridTest, IdsRoundTrip) {
  const TileGrid grid(Area(0.0, 0.0, 59.0, 39.0), 20.0, 5.0);
  for (const TileIndex& t : grid.Tiles()) EXPECT_EQ(grid.Parse(TileGrid::Id(t)), t);
  EXPECT_EQ(TileGrid::Id({2, 1}), "2_1");
  EXPECT_FALSE(grid.Parse("3_0").has_value());
  EXPECT_FALSE(grid.Parse("1_1x").has_value());
  EXPECT_FALSE(grid.Parse("01_1").has_value());
}

TEST(TileGridTest, RejectsBadInputsAndOptions) {
  EXPECT_THROW(TileGrid(Box2d{}, 20.0, 5.0), Error);
  TilingOptions o;
  o.tile_size_m = -1;
  o.z_max_m = o.z_min_m;
  try {
    ValidateTilingOptions(o);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("TilingOptions.tile_size_m = -1: must be >= 0"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("TilingOptions.z_max_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sacfuse
