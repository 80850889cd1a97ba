// The project CRS end to end, with the CRS of the Montpellier LiDAR in ../shared (Lambert-93 + NGF-IGN69 heights,
// issue 46): the simulated tiny block is a workspace in a local frame, `input.origin_m` places it at Montpellier's
// coordinates and `crs: EPSG:2154+5720` names the CRS. The fused LAS must hold the workspace's points moved by the
// origin, carry the CRS that GDAL (gdalsrsinfo) and PROJ (projinfo) read back as Lambert-93 + NGF-IGN69
// (EPSG:5698, the same compound), whose horizontal part is the CRS our reader finds in the Montpellier tiles, and
// `sacfuse validate` names it. The same run with output.format copc in tiles writes a COPC file (and COPC tiles)
// with that CRS record, which GDAL and PROJ read back as EPSG:5698, and its tile index (tiles.vpc) states it.
// The runs use fusion.method union (every depth pixel back-projected, the step every method shares) without
// co-registration: their points show the shift itself. SAC's discrete choices (superpixel labels) amplify the
// last-bit differences between computing at 390,000 m and at 770,500 m into different clouds (0.2 % of the points;
// docs/crs.md), as they would for any two runs whose poses differ in the last bits.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/crs.h"
#include "io/las_crs.h"
#include "io/las_reader.h"
#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;

// The tiny block lies at (390000, 5705000) + [0, 60] m; this origin moves it onto the Montpellier tile
// test_data_77050_627755 (770500..770550 E, 6277500..6277550 N).
const Eigen::Vector3d kOrigin(380500.0, 572500.0, 0.0);

bool HaveTool(const std::string& tool) { return RunCommand("command -v " + tool + " >/dev/null 2>&1") == 0; }

// GDAL and PROJ's own tools (Debian gdal-bin, proj-bin; test-time only) read `wkt` as EPSG:5698, the EPSG code of
// Lambert-93 + NGF-IGN69 heights; GDAL's WKT1 of it names both parts. `wkt_file`: where the WKT is written for them.
void ExpectGdalAndProjReadLambert93Ign69(const std::string& wkt, const fs::path& wkt_file) {
  SCOPED_TRACE(wkt_file.filename().string());
  std::ofstream(wkt_file) << wkt;
  std::string out;
  if (HaveTool("gdalsrsinfo")) {
    ASSERT_EQ(RunCommand("gdalsrsinfo -o epsg " + ShellQuote(wkt_file), &out), 0) << out;
    EXPECT_NE(out.find("EPSG:5698"), std::string::npos) << out;
    ASSERT_EQ(RunCommand("gdalsrsinfo --single-line -o wkt1 " + ShellQuote(wkt_file), &out), 0) << out;
    EXPECT_NE(out.find("AUTHORITY[\"EPSG\",\"2154\"]"), std::string::npos) << out;
    EXPECT_NE(out.find("AUTHORITY[\"EPSG\",\"5720\"]"), std::string::npos) << out;
  } else {
    std::printf("[ crs e2e  ] gdalsrsinfo not installed (Debian gdal-bin): GDAL's reading is not checked\n");
  }
  if (HaveTool("projinfo")) {
    ASSERT_EQ(RunCommand("projinfo --identify -o PROJ \"$(cat " + ShellQuote(wkt_file) + ")\"", &out), 0) << out;
    EXPECT_NE(out.find("EPSG:5698: 100 %"), std::string::npos) << out;
  } else {
    std::printf("[ crs e2e  ] projinfo not installed (Debian proj-bin): PROJ's command line is not asked\n");
  }
}

class CrsEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock();
    Run("local", "");
    Run("montpellier", "crs: \"EPSG:2154+5720\"\n", kOrigin);
    Run("montpellier_copc", "crs: \"EPSG:2154+5720\"\ntiling: {tile_size_m: 30}\n", kOrigin, "copc");
  }

  static void Run(const std::string& name, const std::string& extra, const Eigen::Vector3d& origin = {0, 0, 0},
                  const std::string& format = "las") {
    std::ofstream(Config(name)) << extra << "input: {format: colmap, path: " << Block().string()
                                << ", origin_m: [" << origin.x() << ", " << origin.y() << ", " << origin.z() << "]}\n"
                                << "output: {dir: " << Out(name).string() << ", format: " << format << "}\n"
                                << "fusion: {method: union}\ncoregistration: {enabled: false}\n";
    std::string out;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config(name)), &out), 0) << out;
  }

  static fs::path Cloud(const std::string& name) { return Out(name) / "fused.las"; }

  static std::string WktOf(const fs::path& las) {
    LasReader reader(las.string());
    return ReadLasCrs(reader.header()).wkt;
  }
};

TEST_F(CrsEndToEndTest, PointsAreTheWorkspacesPlusTheOrigin) {
  LasHeader local_header, moved_header;
  const std::vector<LasPoint> local = ReadAllLasPoints(Cloud("local").string(), &local_header);
  const std::vector<LasPoint> moved = ReadAllLasPoints(Cloud("montpellier").string(), &moved_header);
  ASSERT_GT(local.size(), 1000000u);
  ASSERT_EQ(moved.size(), local.size());
  const double scale = local_header.scale.x();
  size_t off = 0, other = 0;
  for (size_t i = 0; i < local.size(); ++i) {
    // Equal stored integers up to the origin (a multiple of the scale): the difference is below half a step.
    off += ((moved[i].xyz - local[i].xyz - kOrigin).cwiseAbs().maxCoeff() > 0.5 * scale) ? 1 : 0;
    other += (moved[i].rgb != local[i].rgb || moved[i].point_source_id != local[i].point_source_id) ? 1 : 0;
  }
  std::printf("[ crs e2e  ] %zu points; %zu not at workspace + origin; LAS offsets (%.0f, %.0f) -> (%.0f, %.0f)\n",
              local.size(), off, local_header.offset.x(), local_header.offset.y(), moved_header.offset.x(),
              moved_header.offset.y());
  // Doubles: a point lands on the other side of a 1 mm quantum only when it lies within ~1e-9 m of the boundary
  // (2026-11-29: 3 of 1,472,067 points).
  EXPECT_LE(off, local.size() / 100000);
  EXPECT_EQ(other, 0u);
  // At Montpellier: the block overlaps the LiDAR tile's extent.
  EXPECT_GT(moved_header.max.x(), 770500.0);
  EXPECT_LT(moved_header.min.x(), 770550.0);
  EXPECT_GT(moved_header.max.y(), 6277500.0);
  EXPECT_LT(moved_header.min.y(), 6277550.0);
}

TEST_F(CrsEndToEndTest, TheCrsOfTheMontpellierLidarIsWrittenAndReadBack) {
  const std::string wkt = WktOf(Cloud("montpellier"));
  ASSERT_FALSE(wkt.empty());
  EXPECT_EQ(WktOf(Cloud("local")), "");
  // Our reader and PROJ: the compound of Lambert-93 and NGF-IGN69 heights.
  const Crs ours = ParseProjectCrs(wkt);
  EXPECT_EQ(ours.Code(), "EPSG:2154+5720");
  EXPECT_EQ(ours.horizontal_epsg(), 2154);
  EXPECT_EQ(ours.vertical_epsg(), 5720);
  // The Montpellier tiles' CRS, as our reader finds it, is the horizontal part.
  const std::optional<fs::path> shared = testing::SharedDir();
  const fs::path tile = shared ? *shared / "research-data/lidar/ign_montpellier/test_data_77050_627755_LA93_IGN69.las"
                               : fs::path();
  if (shared && fs::exists(tile)) {
    LasReader reader(tile.string());
    const LasCrsInfo montpellier = ReadLasCrs(reader.header());
    std::printf("[ crs e2e  ] Montpellier tile: %s\n", montpellier.description.c_str());
    EXPECT_EQ(montpellier.code, "EPSG:2154");
    EXPECT_EQ(ParseProjectCrs(montpellier.wkt).horizontal_epsg(), ours.horizontal_epsg());
    EXPECT_EQ(montpellier.name + " + NGF-IGN69 height", ours.Name());
  } else {
    std::printf("[ crs e2e  ] ../shared absent (SACFUSE_SHARED): the Montpellier tile's CRS is not compared\n");
  }
  // `sacfuse validate` names it.
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " validate " + ShellQuote(Cloud("montpellier")), &out), 0) << out;
  EXPECT_NE(out.find("CRS EPSG:2154+5720 \"RGF93 v1 / Lambert-93 + NGF-IGN69 height\" (WKT1 COMPD_CS"),
            std::string::npos)
      << out;
  ExpectGdalAndProjReadLambert93Ign69(wkt, Dir() / "montpellier.wkt");
}

// output.format copc with the compound CRS: fused.copc.laz and every COPC tile carry the LAS run's CRS record,
// which GDAL and PROJ read back as Lambert-93 + NGF-IGN69; `sacfuse validate` names it and checks the COPC; the
// tile index tiles.vpc states that WKT for every tile (proj:wkt2: the text GDAL and PROJ read above), no
// horizontal-only proj:epsg, and WGS 84 bounds at Montpellier.
TEST_F(CrsEndToEndTest, CopcAndTileIndexCarryTheCompoundCrs) {
  const fs::path copc = Out("montpellier_copc") / "fused.copc.laz";
  const std::string las_wkt = WktOf(Cloud("montpellier"));
  ASSERT_FALSE(las_wkt.empty());
  EXPECT_EQ(WktOf(copc), las_wkt);
  ExpectGdalAndProjReadLambert93Ign69(WktOf(copc), Dir() / "montpellier_copc.wkt");
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " validate " + ShellQuote(copc), &out), 0) << out;
  EXPECT_NE(out.find("CRS EPSG:2154+5720 \"RGF93 v1 / Lambert-93 + NGF-IGN69 height\""), std::string::npos) << out;
  EXPECT_NE(out.find("COPC 1.0"), std::string::npos) << out;

  std::ifstream in(Out("montpellier_copc") / "tiles.vpc");
  const nlohmann::json vpc = nlohmann::json::parse(in);
  ASSERT_GT(vpc.at("features").size(), 1u);
  for (const nlohmann::json& f : vpc.at("features")) {
    const std::string href = f.at("assets").at("data").at("href");
    SCOPED_TRACE(href);
    const fs::path tile = Out("montpellier_copc") / href;
    EXPECT_EQ(WktOf(tile), las_wkt);
    const nlohmann::json& p = f.at("properties");
    EXPECT_EQ(p.at("proj:wkt2").get<std::string>(), las_wkt);
    EXPECT_FALSE(p.contains("proj:epsg")) << p.at("proj:epsg");  // 2154 alone would drop the heights' CRS
    const std::vector<double> wgs84 = f.at("bbox");  // longitude, latitude: Montpellier
    EXPECT_NEAR(wgs84[0], 3.87, 0.05);
    EXPECT_NEAR(wgs84[1], 43.6, 0.05);
  }
}

}  // namespace
}  // namespace sacfuse
