// The DSM's automatic cell (jobs/dsm_product.h AutoDsmCell) and the option rules between the DSM and the tiles.
#include "jobs/dsm_product.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

TEST(DsmProductTest, AutomaticCellIsTwiceTheGsdRoundedAndDividesTheTiles) {
  EXPECT_DOUBLE_EQ(AutoDsmCell(0.10, 0), 0.2);
  EXPECT_DOUBLE_EQ(AutoDsmCell(0.125, 0), 0.25);
  EXPECT_DOUBLE_EQ(AutoDsmCell(0.25, 0), 0.5);
  EXPECT_DOUBLE_EQ(AutoDsmCell(0.23, 0), 0.5);   // 0.46 -> 0.5 (nearest in log scale)
  EXPECT_DOUBLE_EQ(AutoDsmCell(0.17, 0), 0.25);  // 0.34 -> 0.25 (0.34 / 0.25 < 0.5 / 0.34)
  EXPECT_DOUBLE_EQ(AutoDsmCell(0.6, 0), 1.0);
  // A tiled run: the cell must divide the tile edge; 2 m does not divide 25 m, 1 m does.
  EXPECT_DOUBLE_EQ(AutoDsmCell(1.0, 25), 1.0);
  EXPECT_DOUBLE_EQ(AutoDsmCell(0.1, 25), 0.2);
  EXPECT_DOUBLE_EQ(AutoDsmCell(1.2, 32), 2.0);
}

TEST(DsmProductTest, AnExplicitCellThatDoesNotDivideTheTilesIsAConfigError) {
  const std::string yaml =
      "crs: \"EPSG:25832\"\ninput: {path: /nonexistent}\noutput: {dir: /tmp/x, dsm_cell_m: 0.3}\n"
      "tiling: {tile_size_m: 20}\n";
  try {
    ParseJobConfig(yaml, "job.yaml", "/");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("output.dsm_cell_m = 0.3: must divide tiling.tile_size_m (20)"),
              std::string::npos)
        << e.what();
  }
  // With output.dsm: off the cell is not read.
  EXPECT_NO_THROW(ParseJobConfig(
      "input: {path: /nonexistent}\noutput: {dir: /tmp/x, dsm: \"off\", dsm_cell_m: 0.3}\ntiling: {tile_size_m: 20}\n",
      "job.yaml", "/"));
}

TEST(DsmProductTest, DsmIsOnByDefaultOnlyWithAProjectCrs) {
  JobConfig c;
  EXPECT_FALSE(DsmWanted(c));
  c.crs = "EPSG:25832";
  EXPECT_TRUE(DsmWanted(c));
  c.output.dsm = "off";
  EXPECT_FALSE(DsmWanted(c));
  c.crs = "";
  c.output.dsm = "on";
  EXPECT_TRUE(DsmWanted(c));
}

}  // namespace
}  // namespace sacfuse
