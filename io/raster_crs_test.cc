// The CRS written into raster products (io/raster_crs.h): a UTM zone with ellipsoidal heights becomes its horizontal
// CRS, named by its EPSG code, the same text every time.
#include "io/raster_crs.h"

#include <string>

#include <gtest/gtest.h>

#include "core/crs.h"

namespace sacfuse {
namespace {

// WKT1 ends with the CRS's own AUTHORITY node.
bool EndsWithEpsg(const std::string& wkt, const std::string& code) {
  const std::string tail = "AUTHORITY[\"EPSG\",\"" + code + "\"]]";
  return wkt.size() >= tail.size() && wkt.compare(wkt.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(RasterCrsTest, UtmWithEllipsoidalHeightsIsItsHorizontalEpsgCrs) {
  const std::string wkt = RasterCrsWkt(ParseProjectCrs("EPSG:25832"));
  EXPECT_EQ(wkt.rfind("PROJCS[\"ETRS89 / UTM zone 32N\"", 0), 0u) << wkt;
  EXPECT_TRUE(EndsWithEpsg(wkt, "25832")) << wkt;
  EXPECT_EQ(wkt.find("ellipsoidal"), std::string::npos) << wkt;  // no height axis
  EXPECT_EQ(RasterCrsWkt(ParseProjectCrs("EPSG:25832")), wkt);  // the same text on every call
  EXPECT_TRUE(EndsWithEpsg(RasterCrsWkt(ParseProjectCrs("EPSG:32733")), "32733"));
}

TEST(RasterCrsTest, NoCrsGivesNoWkt) { EXPECT_EQ(RasterCrsWkt(ParseProjectCrs("")), ""); }

}  // namespace
}  // namespace sacfuse
