// WriteVirtualPointCloud (io/vpc_writer.h): the .vpc QGIS and PDAL wrench read, for LAZ and COPC files in a
// sub-folder, checked field by field against what our reader says of each file: the STAC layout QGIS's provider
// requires (FeatureCollection; each Feature with stac_version 1.0.0, an object geometry, properties and assets),
// relative hrefs, pc:count, proj:bbox, the CRS record as stored and its EPSG code, and the WGS 84 geometry of a
// UTM run (the corners converted back with core/crs.h: the same metres); a run without a CRS keeps its own
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
  for (const char* crs_text : {"EPSG:25832", ""}) {
    SCOPED_TRACE(crs_text);
    const ProjectCrs crs = ParseProjectCrs(crs_text);
    LasWriterOptions o;
    o.offset = Eigen::Vector3d(390000, 5705000, 0);
    AddCrsToLasOptions(crs, &o);
    const std::vector<std::string> files = {(dir / "tiles" / "0_0.laz").string(),
                                            (dir / "tiles" / "1_0.copc.laz").string()};
    {
      LasWriterOptions laz = o;
      laz.compressed = true;
      LasWriter w(files[0], laz);
      const std::vector<LasPoint> pts = Box(390100, 5705100, 80, 5000);
      w.WritePoints(pts.data(), pts.size());
      w.Close();
      CopcWriter c(files[1], o);
      const std::vector<LasPoint> more = Box(390140, 5705100, 85, 3000);
      c.WritePoints(more.data(), more.size());
      c.Close();
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
      EXPECT_EQ(p.contains("proj:epsg"), crs.georeferenced());
      if (crs.georeferenced()) {
        EXPECT_EQ(p.at("proj:epsg"), 25832);
      }
      EXPECT_EQ(p.at("pc:schemas").size(), 18u);  // PDRF 7 as PDAL lists it
      const json& ring = f.at("geometry").at("coordinates")[0];
      ASSERT_EQ(ring.size(), 5u);
      const double corners[4][2] = {{h.min.x(), h.min.y()}, {h.max.x(), h.min.y()}, {h.max.x(), h.max.y()},
                                    {h.min.x(), h.max.y()}};
      for (int k = 0; k < 4; ++k) {
        const double a = ring[k][0], b = ring[k][1];
        if (crs.georeferenced()) {
          // Longitude, latitude near Dortmund, back to the same metres.
          EXPECT_NEAR(a, 7.4, 0.2);
          EXPECT_NEAR(b, 51.5, 0.2);
          const Eigen::Vector3d back = ProjectFromGeodetic(crs, b, a, 0.0);
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
