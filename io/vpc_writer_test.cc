// WriteVirtualPointCloud (io/vpc_writer.h): the .vpc QGIS and PDAL wrench read, for LAZ and COPC files in a
// sub-folder, checked field by field against what our reader says of each file: the STAC layout QGIS's provider
// requires (FeatureCollection; each Feature with stac_version 1.0.0, an object geometry, properties and assets),
// relative hrefs, pc:count, proj:bbox, the CRS record as stored and its EPSG code (none for a compound named by two
// codes: proj:wkt2 carries it), and the WGS 84 geometry of a UTM and a Lambert-93 + NGF-IGN69 run (the corners
// converted back with io/crs.h: the same metres; no geoid grid needed); a run without a CRS keeps its own
// coordinates and writes no EPSG code.
#include "io/vpc_writer.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/copc_writer.h"
#include "io/las_crs.h"
#include "io/las_reader.h"
#include "io/las_writer.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::TempDir;

std::vector<LasPoint> Box(double x0, double y0, double z0, size_t n) {
  std::vector<LasPoint> pts(n);
  for (size_t i = 0; i < n; ++i) {
    pts[i].xyz = {x0 + 0.37 * static_cast<double>(i % 97), y0 + 0.29 * static_cast<double>(i / 97),
                  z0 + 0.01 * static_cast<double>(i % 13)};
  }
  return pts;
}

TEST(VpcWriterTest, IndexesLazAndCopcFilesAsPdalWrenchDoes) {
  TempDir dir;
  fs::create_directories(dir / "tiles");
  struct Case {
    const char* crs;
    const char* horizontal;  // the 2D CRS that converts latitude/longitude back without a geoid
    double x0, y0;           // where the points lie
    double lon, lat;         // near there
    int epsg;                // proj:epsg; 0: none
  };
  const Case cases[] = {{"EPSG:25832", "EPSG:25832", 390000, 5705000, 7.4, 51.5, 25832},
                        {"EPSG:2154+5720", "EPSG:2154", 770000, 6277000, 3.87, 43.6, 0},
                        {"", "", 390000, 5705000, 0, 0, 0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.crs);
    const Crs crs = ParseProjectCrs(c.crs);
    LasWriterOptions o;
    o.offset = Eigen::Vector3d(c.x0, c.y0, 0);
    AddCrsToLasOptions(crs, &o);
    const std::vector<std::string> files = {(dir / "tiles" / "0_0.laz").string(),
                                            (dir / "tiles" / "1_0.copc.laz").string()};
    {
      LasWriterOptions laz = o;
      laz.compressed = true;
      LasWriter w(files[0], laz);
      const std::vector<LasPoint> pts = Box(c.x0 + 100, c.y0 + 100, 80, 5000);
      w.WritePoints(pts.data(), pts.size());
      w.Close();
      CopcWriter copc(files[1], o);
      const std::vector<LasPoint> more = Box(c.x0 + 140, c.y0 + 100, 85, 3000);
      copc.WritePoints(more.data(), more.size());
      copc.Close();
    }
    const fs::path vpc = dir / "tiles.vpc";
    WriteVirtualPointCloud(vpc.string(), files, crs);
    std::ifstream in(vpc);
    const json j = json::parse(in);
    ASSERT_EQ(j.at("type"), "FeatureCollection");
    ASSERT_EQ(j.at("features").size(), 2u);
    for (size_t i = 0; i < files.size(); ++i) {
      const json& f = j.at("features")[i];
      LasHeader h;
      {
        LasReader reader(files[i]);
        h = reader.header();
      }
      EXPECT_EQ(f.at("type"), "Feature");
      EXPECT_EQ(f.at("stac_version"), "1.0.0");
      EXPECT_TRUE(f.at("geometry").is_object());
      EXPECT_EQ(f.at("id"), i == 0 ? "0_0" : "1_0");
      const std::string href = f.at("assets").at("data").at("href");
      EXPECT_EQ(href, i == 0 ? "./tiles/0_0.laz" : "./tiles/1_0.copc.laz");
      const json& p = f.at("properties");
      EXPECT_EQ(p.at("pc:count").get<uint64_t>(), h.point_count);
      const std::vector<double> bbox = p.at("proj:bbox");
      EXPECT_EQ(bbox, (std::vector<double>{h.min.x(), h.min.y(), h.min.z(), h.max.x(), h.max.y(), h.max.z()}));
      EXPECT_EQ(p.at("proj:wkt2"), ReadLasCrs(h).wkt);
      EXPECT_EQ(p.contains("proj:epsg"), c.epsg != 0);
      if (c.epsg != 0) {
        EXPECT_EQ(p.at("proj:epsg"), c.epsg);
      }
      EXPECT_EQ(p.at("pc:schemas").size(), 18u);  // PDRF 7 as PDAL lists it
      const json& ring = f.at("geometry").at("coordinates")[0];
      ASSERT_EQ(ring.size(), 5u);
      const double corners[4][2] = {{h.min.x(), h.min.y()}, {h.max.x(), h.min.y()}, {h.max.x(), h.max.y()},
                                    {h.min.x(), h.max.y()}};
      for (int k = 0; k < 4; ++k) {
        const double a = ring[k][0], b = ring[k][1];
        if (crs.georeferenced()) {
          // Longitude, latitude near the place, back to the same metres.
          EXPECT_NEAR(a, c.lon, 0.2);
          EXPECT_NEAR(b, c.lat, 0.2);
          const Eigen::Vector3d back = ProjectFromGeodetic(ParseProjectCrs(c.horizontal), b, a, 0.0);
          EXPECT_NEAR(back.x(), corners[k][0], 1e-6);
          EXPECT_NEAR(back.y(), corners[k][1], 1e-6);
        } else {
          EXPECT_EQ(a, corners[k][0]);
          EXPECT_EQ(b, corners[k][1]);
        }
      }
      EXPECT_EQ(ring[4], ring[0]);
    }
  }
}

}  // namespace
}  // namespace sacfuse
