#include "io/las_crs.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/crs_wkt.h"
#include "io/las_format.h"
#include "io/las_reader.h"
#include "io/las_validate.h"
#include "io/las_writer.h"
#include "io/wkt1.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using testing::TempDir;

// PROJ 9.1.1's WKT1 (`projinfo EPSG:25832 -o WKT1_GDAL --single-line`, and the same for 32632, 32733, and
// EPSG:2154+5720): a statement of these CRSs by PROJ's command-line tool, which what we write must reproduce
// character for character.
const char* kProj25832 =
    "PROJCS[\"ETRS89 / UTM zone 32N\",GEOGCS[\"ETRS89\",DATUM[\"European_Terrestrial_Reference_System_1989\","
    "SPHEROID[\"GRS 1980\",6378137,298.257222101,AUTHORITY[\"EPSG\",\"7019\"]],AUTHORITY[\"EPSG\",\"6258\"]],"
    "PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\","
    "\"9122\"]],AUTHORITY[\"EPSG\",\"4258\"]],PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],"
    "PARAMETER[\"central_meridian\",9],PARAMETER[\"scale_factor\",0.9996],PARAMETER[\"false_easting\",500000],"
    "PARAMETER[\"false_northing\",0],UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],"
    "AXIS[\"Northing\",NORTH],AUTHORITY[\"EPSG\",\"25832\"]]";
const char* kProj32632 =
    "PROJCS[\"WGS 84 / UTM zone 32N\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,"
    "AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],"
    "UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],AUTHORITY[\"EPSG\",\"4326\"]],"
    "PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],PARAMETER[\"central_meridian\",9],"
    "PARAMETER[\"scale_factor\",0.9996],PARAMETER[\"false_easting\",500000],PARAMETER[\"false_northing\",0],"
    "UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH],"
    "AUTHORITY[\"EPSG\",\"32632\"]]";
const char* kProj32733 =
    "PROJCS[\"WGS 84 / UTM zone 33S\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,"
    "AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],"
    "UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],AUTHORITY[\"EPSG\",\"4326\"]],"
    "PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],PARAMETER[\"central_meridian\",15],"
    "PARAMETER[\"scale_factor\",0.9996],PARAMETER[\"false_easting\",500000],PARAMETER[\"false_northing\",10000000],"
    "UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH],"
    "AUTHORITY[\"EPSG\",\"32733\"]]";

const char* kProj2154Plus5720 =
    "COMPD_CS[\"RGF93 v1 / Lambert-93 + NGF-IGN69 height\",PROJCS[\"RGF93 v1 / Lambert-93\",GEOGCS[\"RGF93 v1\","
    "DATUM[\"Reseau_Geodesique_Francais_1993_v1\",SPHEROID[\"GRS 1980\",6378137,298.257222101,AUTHORITY[\"EPSG\","
    "\"7019\"]],AUTHORITY[\"EPSG\",\"6171\"]],PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\","
    "0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],AUTHORITY[\"EPSG\",\"4171\"]],PROJECTION["
    "\"Lambert_Conformal_Conic_2SP\"],PARAMETER[\"latitude_of_origin\",46.5],PARAMETER[\"central_meridian\",3],"
    "PARAMETER[\"standard_parallel_1\",49],PARAMETER[\"standard_parallel_2\",44],PARAMETER[\"false_easting\",700000],"
    "PARAMETER[\"false_northing\",6600000],UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],"
    "AXIS[\"Northing\",NORTH],AUTHORITY[\"EPSG\",\"2154\"]],VERT_CS[\"NGF-IGN69 height\",VERT_DATUM["
    "\"Nivellement General de la France - IGN69\",2005,AUTHORITY[\"EPSG\",\"5119\"]],UNIT[\"metre\",1,AUTHORITY["
    "\"EPSG\",\"9001\"]],AXIS[\"Gravity-related height\",UP],AUTHORITY[\"EPSG\",\"5720\"]]]";

std::vector<uint16_t> AsU16(const std::vector<uint8_t>& bytes) {
  std::vector<uint16_t> out(bytes.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) out[i] = las_format::GetU16(&bytes[2 * i]);
  return out;
}

std::string Parameter(const WktNode& projcs, const std::string& name) {
  for (const WktNode& c : projcs.children) {
    if (c.keyword == "PARAMETER" && c.values.size() == 2 && c.values[0] == name) return c.values[1];
  }
  return "?";
}

std::string Las14Wkt(const std::string& crs) { return ProjectCrsWkt(crs, CrsWktDialect::kLas14); }

TEST(LasCrsWkt, ProjectedIsProjsWkt1PlusEllipsoidalHeightsInMetres) {
  struct Case {
    const char* crs;
    const char* projcs;
    int epsg;
  };
  for (const Case& c : {Case{"EPSG:25832", kProj25832, 25832}, Case{"EPSG:32632", kProj32632, 32632},
                        Case{"EPSG:32733", kProj32733, 32733}}) {
    const Crs crs = ParseProjectCrs(c.crs);
    const std::string wkt = Las14Wkt(c.crs);
    EXPECT_EQ(wkt, "COMPD_CS[\"" + crs.Name() + " + Ellipsoid (metre)\"," + c.projcs +
                       ",VERT_CS[\"Ellipsoid (metre)\",VERT_DATUM[\"Ellipsoid\",2002],UNIT[\"metre\",1,AUTHORITY["
                       "\"EPSG\",\"9001\"]],AXIS[\"Ellipsoidal height\",UP]]]");
    const WktNode root = ParseWkt1(wkt);
    EXPECT_EQ(root.keyword, "COMPD_CS");
    EXPECT_EQ(WktHorizontalEpsg(root), c.epsg);
    ASSERT_NE(root.Child("VERT_CS"), nullptr);
    const WktNode* unit = root.Child("VERT_CS")->Child("UNIT");
    ASSERT_NE(unit, nullptr);
    EXPECT_EQ(unit->values, (std::vector<std::string>{"metre", "1"}));
    EXPECT_EQ(root.Child("VERT_CS")->Child("VERT_DATUM")->values[1], "2002");  // ellipsoidal
  }
  const WktNode south = ParseWkt1(Las14Wkt("EPSG:32701"));
  EXPECT_EQ(Parameter(*south.Child("PROJCS"), "central_meridian"), "-177");
  EXPECT_EQ(Parameter(*south.Child("PROJCS"), "false_northing"), "10000000");
  EXPECT_EQ(Las14Wkt(""), "");
  EXPECT_EQ(ProjectCrsWkt("", CrsWktDialect::kGdal), "");
  EXPECT_THROW(Las14Wkt("EPSG:4326"), ConfigError);
}

TEST(LasCrsWkt, CompoundIsProjsWkt1WithTheVerticalCrs) {
  EXPECT_EQ(Las14Wkt("EPSG:2154+5720"), kProj2154Plus5720);
  EXPECT_EQ(Las14Wkt(" EPSG:2154+5720 "), kProj2154Plus5720);
  // For GDAL: WKT2:2019 of the CRS as named (GDAL writes its GeoTIFF keys from it).
  const std::string wkt2 = ProjectCrsWkt("EPSG:2154+5720", CrsWktDialect::kGdal);
  EXPECT_EQ(wkt2.rfind("COMPOUNDCRS[\"RGF93 v1 / Lambert-93 + NGF-IGN69 height\",PROJCRS[", 0), 0u) << wkt2;
  EXPECT_NE(wkt2.find("ID[\"EPSG\",5720]"), std::string::npos) << wkt2;
  EXPECT_EQ(ProjectCrsWkt("EPSG:25832", CrsWktDialect::kGdal).rfind("PROJCRS[\"ETRS89 / UTM zone 32N\"", 0), 0u);
}

TEST(LasCrsWkt, LocalEnuIsALocalCsNamingItsOrigin) {
  const std::string wkt = Las14Wkt("ENU:51.5,7.46,120");
  EXPECT_EQ(ProjectCrsWkt("ENU:51.5,7.46,120", CrsWktDialect::kGdal), wkt);
  const WktNode root = ParseWkt1(wkt);
  EXPECT_EQ(root.keyword, "LOCAL_CS");
  ASSERT_FALSE(root.values.empty());
  EXPECT_EQ(root.values[0], "sacfuse local ENU: origin lat 51.5, lon 7.46, h 120 m (WGS 84 ellipsoid); z = up, metres");
  ASSERT_NE(root.Child("UNIT"), nullptr);
  EXPECT_EQ(root.Child("UNIT")->values[0], "metre");
  std::vector<std::string> axes;
  for (const WktNode& c : root.children) {
    if (c.keyword == "AXIS") axes.push_back(c.values[1]);
  }
  EXPECT_EQ(axes, (std::vector<std::string>{"EAST", "NORTH"}));
  EXPECT_EQ(WktHorizontalEpsg(root), 0);
}

TEST(LasCrsWkt, ParserHandlesQuotesParenthesesAndRejectsGarbage) {
  const WktNode n = ParseWkt1(" GEOGCS ( \"a \"\"b\"\"\" , 1.5e3 , AXIS[\"Lat\", NORTH] ) ");
  EXPECT_EQ(n.keyword, "GEOGCS");
  EXPECT_EQ(n.values, (std::vector<std::string>{"a \"b\"", "1.5e3"}));
  ASSERT_EQ(n.children.size(), 1u);
  EXPECT_EQ(n.children[0].values, (std::vector<std::string>{"Lat", "NORTH"}));
  for (const std::string bad : {"", "PROJCS", "PROJCS[\"x\"", "PROJCS[\"x\"]]", "PROJCS[\"x\",]", "PROJCS[\"x]",
                                "PROJCS[\"x\") ", "PROJCS[\"x\"] trailing"}) {
    EXPECT_THROW(ParseWkt1(bad), Error) << bad;
  }
}

TEST(LasCrsRecords, Las14GetsOneNulTerminatedWktRecordAndTheWktBit) {
  const Crs crs = ParseProjectCrs("EPSG:25832");
  const LasCrsRecords r = LasCrsVlrs(crs, 4);
  EXPECT_EQ(r.global_encoding_bits, 0x10);
  ASSERT_EQ(r.vlrs.size(), 1u);
  EXPECT_EQ(r.vlrs[0].user_id, "LASF_Projection");
  EXPECT_EQ(r.vlrs[0].record_id, 2112);
  EXPECT_FALSE(r.vlrs[0].extended);
  ASSERT_FALSE(r.vlrs[0].data.empty());
  EXPECT_EQ(r.vlrs[0].data.back(), 0);
  EXPECT_EQ(std::string(r.vlrs[0].data.begin(), r.vlrs[0].data.end() - 1), Las14Wkt("EPSG:25832"));
  const LasCrsRecords none = LasCrsVlrs(ParseProjectCrs(""), 4);
  EXPECT_TRUE(none.vlrs.empty());
  EXPECT_EQ(none.global_encoding_bits, 0);
  EXPECT_THROW(LasCrsVlrs(crs, 3), Error);
}

TEST(LasCrsRecords, Las12GetsGeoKeysByteForByte) {
  const LasCrsRecords r = LasCrsVlrs(ParseProjectCrs("EPSG:25832"), 2);
  EXPECT_EQ(r.global_encoding_bits, 0);
  ASSERT_EQ(r.vlrs.size(), 2u);
  EXPECT_EQ(r.vlrs[0].user_id, "LASF_Projection");
  EXPECT_EQ(r.vlrs[0].record_id, 34735);
  EXPECT_EQ(r.vlrs[1].record_id, 34737);
  const std::string citation = "ETRS89 / UTM zone 32N (EPSG:25832), ellipsoidal heights, metre";
  const uint16_t len = static_cast<uint16_t>(citation.size() + 1);
  // {version 1, revision 1.0, 5 keys}, then {id, location, count, value} in ascending id order.
  EXPECT_EQ(AsU16(r.vlrs[0].data), (std::vector<uint16_t>{1, 1, 0, 5,                //
                                                          1024, 0, 1, 1,             // projected
                                                          1026, 34737, len, 0,       // citation
                                                          3072, 0, 1, 25832,         // EPSG
                                                          3076, 0, 1, 9001,          // metre
                                                          4099, 0, 1, 9001}));       // vertical metre
  EXPECT_EQ(std::string(r.vlrs[1].data.begin(), r.vlrs[1].data.end()), citation + "|" + std::string(1, '\0'));

  // Lambert-93 + NGF-IGN69: the vertical CRS as VerticalCSTypeGeoKey.
  const LasCrsRecords lambert = LasCrsVlrs(ParseProjectCrs("EPSG:2154+5720"), 2);
  const std::string lambert_citation =
      "RGF93 v1 / Lambert-93 + NGF-IGN69 height (EPSG:2154+5720), NGF-IGN69 height, metre";
  const uint16_t lambert_len = static_cast<uint16_t>(lambert_citation.size() + 1);
  EXPECT_EQ(AsU16(lambert.vlrs[0].data), (std::vector<uint16_t>{1, 1, 0, 6,                  //
                                                                1024, 0, 1, 1,               // projected
                                                                1026, 34737, lambert_len, 0,  // citation
                                                                3072, 0, 1, 2154,            // EPSG
                                                                3076, 0, 1, 9001,            // metre
                                                                4096, 0, 1, 5720,            // NGF-IGN69
                                                                4099, 0, 1, 9001}));         // vertical metre
  LasHeader lh;
  lh.vlrs = lambert.vlrs;
  const LasCrsInfo lambert_info = ReadLasCrs(lh);
  EXPECT_EQ(lambert_info.epsg, 2154);
  EXPECT_EQ(lambert_info.code, "EPSG:2154+5720");
  EXPECT_EQ(lambert_info.name, "RGF93 v1 / Lambert-93 + NGF-IGN69 height");
  // GeoTIFF keys name EPSG codes only: a CRS without one cannot go into LAS 1.2.
  const Crs custom = ParseProjectCrs("+proj=utm +zone=32 +ellps=GRS80 +units=m +type=crs");
  EXPECT_NE(LasCrsProblem(custom, 2).find("EPSG code"), std::string::npos);
  EXPECT_EQ(LasCrsProblem(custom, 4), "");
  EXPECT_THROW(LasCrsVlrs(custom, 2), Error);
  EXPECT_EQ(LasCrsVlrs(custom, 4).vlrs.size(), 1u);

  const LasCrsRecords enu = LasCrsVlrs(ParseProjectCrs("ENU:51.5,7.46,120"), 2);
  ASSERT_EQ(enu.vlrs.size(), 2u);
  const std::vector<uint16_t> keys = AsU16(enu.vlrs[0].data);
  ASSERT_EQ(keys.size(), 16u);
  EXPECT_EQ((std::vector<uint16_t>(keys.begin() + 4, keys.begin() + 8)), (std::vector<uint16_t>{1024, 0, 1, 32767}));
  LasHeader h;
  h.vlrs = enu.vlrs;
  const LasCrsInfo info = ReadLasCrs(h);
  EXPECT_EQ(info.epsg, 0);  // user-defined
  EXPECT_NE(info.description.find("model type 32767"), std::string::npos) << info.description;
  EXPECT_NE(info.description.find("local ENU at 51.5, 7.46, 120 m"), std::string::npos) << info.description;
}

TEST(LasCrsRecords, AddingToWriterOptionsKeepsOtherVlrsAndRefusesASecondCrs) {
  LasWriterOptions o;
  LasVlr other;
  other.user_id = "sacfuse";
  other.record_id = 1;
  o.vlrs.push_back(other);
  o.global_encoding_extra_bits = 0x1;
  AddCrsToLasOptions(ParseProjectCrs("EPSG:32632"), &o);
  ASSERT_EQ(o.vlrs.size(), 2u);
  EXPECT_EQ(o.vlrs[0].user_id, "sacfuse");
  EXPECT_EQ(o.global_encoding_extra_bits, 0x11);
  EXPECT_THROW(AddCrsToLasOptions(ParseProjectCrs("EPSG:32632"), &o), Error);
  LasWriterOptions plain;
  AddCrsToLasOptions(ParseProjectCrs(""), &plain);
  EXPECT_TRUE(plain.vlrs.empty());
  EXPECT_EQ(plain.global_encoding_extra_bits, 0);
}

// Writes a small file with our writer carrying `crs`, reads it back.
std::string WriteWithCrs(const TempDir& dir, const std::string& name, const std::string& crs_text, int minor) {
  const std::string path = (dir / name).string();
  LasWriterOptions o;
  o.version_minor = minor;
  AddCrsToLasOptions(ParseProjectCrs(crs_text), &o);
  LasWriter w(path, o);
  std::vector<FusedPoint> pts(100);
  for (size_t i = 0; i < pts.size(); ++i) {
    pts[i].point_in_world = {395883.554 + 0.5 * i, 5706495.877 - 0.25 * i, 100.0 + 0.01 * i};
    pts[i].rgb = {static_cast<uint8_t>(i), 20, 30};
    pts[i].view_index = static_cast<uint32_t>(i % 7);
  }
  w.Write(pts.data(), pts.size());
  w.Close();
  return path;
}

TEST(LasCrsRecords, WrittenFilesReadBackWithTheirCrsAndValidate) {
  TempDir dir;
  for (const char* crs : {"EPSG:25832", "EPSG:32632", "EPSG:2154+5720", "ENU:51.5,7.46,120", ""}) {
    for (int minor : {2, 4}) {
      SCOPED_TRACE(std::string(crs) + " 1." + std::to_string(minor));
      const std::string path = WriteWithCrs(dir, "f" + std::to_string(minor) + ".las", crs, minor);
      LasReader reader(path);
      const LasHeader& h = reader.header();
      const LasCrsInfo info = ReadLasCrs(h);
      const Crs parsed = ParseProjectCrs(crs);
      EXPECT_EQ(info.epsg, parsed.horizontal_epsg());
      EXPECT_EQ((h.global_encoding & 0x10) != 0, minor == 4 && parsed.georeferenced());
      EXPECT_EQ(info.wkt_records, minor == 4 && parsed.georeferenced() ? 1 : 0);
      EXPECT_EQ(info.geokey_records, minor == 2 && parsed.georeferenced() ? 1 : 0);
      if (minor == 4 && parsed.georeferenced()) {
        EXPECT_EQ(info.wkt, Las14Wkt(crs));
      }
      if (parsed.kind() == Crs::Kind::kProjected) {
        // PROJ reads back the CRS written: its name and, for a compound, the code of both parts.
        EXPECT_NE(info.name.find(parsed.Name()), std::string::npos) << info.name;
        EXPECT_EQ(info.code, parsed.orthometric() || minor == 2 ? parsed.Code() : std::string()) << info.description;
        EXPECT_NE(info.description.find("\"" + info.name + "\""), std::string::npos) << info.description;
      }
      if (!parsed.georeferenced()) {
        EXPECT_EQ(info.description, "none");
      }
      EXPECT_EQ(ValidateLasFile(path), std::vector<std::string>{});
    }
  }
}

TEST(LasCrsRead, MalformedGeoKeysAreErrorsNamingTheProblem) {
  LasHeader h;
  h.vlrs = LasCrsVlrs(ParseProjectCrs("EPSG:25832"), 2).vlrs;
  EXPECT_EQ(ParseLasGeoKeys(h).size(), 5u);
  LasHeader short_dir = h;
  short_dir.vlrs[0].data.resize(30);
  EXPECT_THROW(ParseLasGeoKeys(short_dir), Error);
  LasHeader no_ascii = h;
  no_ascii.vlrs.pop_back();
  try {
    ParseLasGeoKeys(no_ascii);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("GTCitationGeoKey"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("34737"), std::string::npos) << e.what();
  }
  LasHeader short_ascii = h;
  short_ascii.vlrs[1].data.resize(5);
  EXPECT_THROW(ParseLasGeoKeys(short_ascii), Error);
  // A foreign directory without GTModelType still yields its projected code; a geographic one its code.
  LasHeader foreign;
  LasVlr dir;
  dir.user_id = "LASF_Projection";
  dir.record_id = 34735;
  for (uint16_t v : {1, 1, 0, 1, 3072, 0, 1, 26915}) {
    dir.data.push_back(static_cast<uint8_t>(v));
    dir.data.push_back(static_cast<uint8_t>(v >> 8));
  }
  foreign.vlrs = {dir};
  EXPECT_EQ(ReadLasCrs(foreign).epsg, 26915);
}

}  // namespace
}  // namespace sacfuse
