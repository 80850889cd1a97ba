// The CRS a raster gets from a point cloud file's CRS record (io/raster_crs.h): our LAS 1.4 WKT of a projected CRS
// with ellipsoidal heights becomes its horizontal CRS, named by its EPSG code, the same text every time; a compound
// CRS with a vertical CRS keeps it.
#include "io/raster_crs.h"

#include <string>

#include <gtest/gtest.h>

#include "io/crs_wkt.h"

namespace sacfuse {
namespace {

// WKT1 ends with the CRS's own AUTHORITY node.
bool EndsWithEpsg(const std::string& wkt, const std::string& code) {
  const std::string tail = "AUTHORITY[\"EPSG\",\"" + code + "\"]]";
  return wkt.size() >= tail.size() && wkt.compare(wkt.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(RasterCrsTest, EllipsoidalHeightsGiveTheHorizontalEpsgCrs) {
  const std::string las_wkt = ProjectCrsWkt("EPSG:25832", CrsWktDialect::kLas14);
  ASSERT_EQ(las_wkt.rfind("COMPD_CS[", 0), 0u) << las_wkt;
  const std::string wkt = RasterCrsWktOf(las_wkt);
  EXPECT_EQ(wkt.rfind("PROJCS[\"ETRS89 / UTM zone 32N\"", 0), 0u) << wkt;
  EXPECT_TRUE(EndsWithEpsg(wkt, "25832")) << wkt;
  EXPECT_EQ(wkt.find("Ellipsoid (metre)"), std::string::npos) << wkt;  // no height axis
  EXPECT_EQ(RasterCrsWktOf(las_wkt), wkt);                             // the same text on every call
  EXPECT_TRUE(EndsWithEpsg(RasterCrsWktOf(ProjectCrsWkt("EPSG:32733", CrsWktDialect::kLas14)), "32733"));
}

TEST(RasterCrsTest, CompoundWithAVerticalCrsAndLocalFramesStayAsTheyAre) {
  const std::string compound = ProjectCrsWkt("EPSG:2154+5720", CrsWktDialect::kLas14);
  EXPECT_EQ(RasterCrsWktOf(compound), compound);
  const std::string enu = ProjectCrsWkt("ENU:51.5,7.46,120", CrsWktDialect::kLas14);
  EXPECT_EQ(RasterCrsWktOf(enu), enu);
  EXPECT_EQ(RasterCrsWktOf(""), "");
}

}  // namespace
}  // namespace sacfuse
