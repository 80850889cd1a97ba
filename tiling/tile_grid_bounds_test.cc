// Tile grids that would be absurdly fine are refused where the grid is made, with a message naming
// tiling.tile_size_m, its value, the area, the tile count and the limit (issue 14: 0.5 m planned 89,055 tiles for
// 20 minutes, 0.001 m ended in a bare std::bad_alloc).
#include "tiling/tile_grid.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/error_of.h"

namespace sacfuse {
namespace {

using testing::ErrorOf;

Box2d Area(double x0, double y0, double x1, double y1) {
  Box2d b;
  b.Extend(Eigen::Vector2d(x0, y0));
  b.Extend(Eigen::Vector2d(x1, y1));
  return b;
}

// Nadir camera 100 m above (x, 0): f = 1000 px, so 0.1 m GSD on z = 0.
View NadirView(double x) {
  View v;
  v.camera = PinholeCamera::Centered(1000, 1000, 1000.0);
  v.cam_from_world.rotation = Eigen::Quaterniond(0, 1, 0, 0);
  v.cam_from_world.translation = v.cam_from_world.rotation * Eigen::Vector3d(-x, 0, -100);
  return v;
}

TEST(TileGridBoundsTest, MillimetreTilesAreRefusedUpFrontNamingKeyValueAreaCountAndLimit) {
  const std::string err = ErrorOf<ConfigError>([] { TileGrid(Area(0, 0, 150, 140), 0.001, 5.0); });
  EXPECT_NE(err.find("tiling.tile_size_m = 0.001: the project area of 150 x 140 m would be cut into"),
            std::string::npos) << err;
  EXPECT_NE(err.find("tiles, more than the limit of 100000"), std::string::npos) << err;
  EXPECT_NE(err.find("use tiles of at least"), std::string::npos) << err;
}

TEST(TileGridBoundsTest, HugeCountsDoNotOverflow) {
  const std::string err = ErrorOf<ConfigError>([] { TileGrid(Area(-1e7, -1e7, 1e7, 1e7), 1e-6, 0.0); });
  EXPECT_NE(err.find("more than the limit of 100000"), std::string::npos) << err;
}

TEST(TileGridBoundsTest, GridsAtTheLimitAreAllowed) {
  const TileGrid grid(Area(0, 0, 99.5, 99.5), 1.0, 0.0);  // 100 x 100 tiles
  EXPECT_EQ(grid.size(), 10000u);
  EXPECT_NO_THROW(TileGrid(Area(0, 0, 315, 315), 1.0, 0.0));  // 316^2 = 99,856 tiles
  EXPECT_THROW(TileGrid(Area(0, 0, 317, 317), 1.0, 0.0), ConfigError);  // 318^2 = 101,124
}

TEST(TileGridBoundsTest, TilesBelowAFewGsdAreRefusedWhenTheGsdIsKnown) {
  const std::string err = ErrorOf<ConfigError>([] { TileGrid(Area(0, 0, 20, 20), 0.5, 5.0, 0.1); });
  EXPECT_NE(err.find("tiling.tile_size_m = 0.5: below 10 ground sampling distances of the block (GSD 0.1 m, so at "
                     "least 1 m)"),
            std::string::npos) << err;
  EXPECT_NO_THROW(TileGrid(Area(0, 0, 20, 20), 1.0, 5.0, 0.1));
  EXPECT_NO_THROW(TileGrid(Area(0, 0, 20, 20), 0.5, 5.0));  // GSD unknown: only the count bound
}

TEST(TileGridBoundsTest, NonFiniteSizesAreErrors) {
  EXPECT_THROW(TileGrid(Area(0, 0, 20, 20), std::numeric_limits<double>::infinity(), 5.0), Error);
  EXPECT_THROW(TileGrid(Area(0, 0, 20, 20), std::nan(""), 5.0), Error);
  EXPECT_THROW(TileGrid(Area(0, 0, 20, 20), 10.0, std::numeric_limits<double>::infinity()), Error);
}

TEST(TileGridBoundsTest, BlockGsdIsTheMedianDepthOverFocal) {
  EXPECT_NEAR(BlockGsdAtHeight({NadirView(0), NadirView(50), NadirView(90)}, 0.0), 0.1, 1e-12);
  EXPECT_NEAR(BlockGsdAtHeight({NadirView(0)}, 50.0), 0.05, 1e-12);
  EXPECT_EQ(BlockGsdAtHeight({NadirView(0)}, 200.0), 0.0);  // plane above the camera: not seen
  EXPECT_EQ(BlockGsdAtHeight({}, 0.0), 0.0);
}

}  // namespace
}  // namespace sacfuse
