// The top-level `crs` key: parsed, validated at load with a message naming the key, value and rule, shown by
// --print-defaults, and part of the result-affecting settings (a changed CRS recomputes tiles).
#include <algorithm>

#include <gtest/gtest.h>

#include "config/config_test_util.h"
#include "config/job_config.h"
#include "config/result_settings.h"
#include "core/error.h"

namespace sacfuse {
namespace {

std::string ErrorOf(const std::string& yaml) { return ConfigErrorOf(yaml); }

TEST(JobConfigCrsTest, DefaultsToNotGeoreferenced) {
  const JobConfig c = ParseJobConfig("input: {path: ws}\n", "job.yaml", "/base");
  EXPECT_EQ(c.crs, "");
}

TEST(JobConfigCrsTest, AcceptsTheSupportedForms) {
  for (const std::string crs : {"EPSG:25832", "EPSG:32633", "EPSG:32733", "ENU:51.5,7.46,120", "", "EPSG:2154",
                                "EPSG:2154+5720", "EPSG:5698"}) {
    const JobConfig c = ParseJobConfig("crs: \"" + crs + "\"\ninput: {path: ws}\n", "job.yaml", "/base");
    EXPECT_EQ(c.crs, crs);
  }
}

TEST(JobConfigCrsTest, RejectsOthersNamingKeyLineValueAndWhatIsSupported) {
  const std::string err = ErrorOf("input: {path: ws}\ncrs: EPSG:4326\n");
  EXPECT_NE(err.find("job.yaml:2: crs = \"EPSG:4326\": \"WGS 84\" is a geographic 2D CRS (latitude/longitude): the "
                     "project CRS must be projected"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("crs takes"), std::string::npos) << err;
  EXPECT_NE(err.find("EPSG:2154+5720"), std::string::npos) << err;
  const std::string enu = ErrorOf("crs: \"ENU:95,7,0\"\ninput: {path: ws}\n");
  EXPECT_NE(enu.find("job.yaml:1: crs = \"ENU:95,7,0\": ENU origin latitude must be in [-90, 90]"), std::string::npos)
      << enu;
  // Reported together with the other problems of the file.
  const std::string both = ErrorOf("crs: UTM32\ninput: {path: ws}\noutput: {scale_m: 0.003}\n");
  EXPECT_NE(both.find("crs = \"UTM32\""), std::string::npos) << both;
  EXPECT_NE(both.find("output.scale_m = 0.003"), std::string::npos) << both;
  // Built in code and validated.
  JobConfig c;
  c.input.path = "ws";
  c.crs = "EPSG:2263";  // feet
  EXPECT_THROW(ValidateJobConfig(c), ConfigError);
}

TEST(JobConfigCrsTest, Las12NeedsACrsItsGeoKeysCanName) {
  const std::string custom = "crs: \"+proj=utm +zone=32 +ellps=GRS80 +units=m +type=crs\"\ninput: {path: ws}\n";
  EXPECT_NO_THROW(ParseJobConfig(custom, "job.yaml", "/base"));
  const std::string err = ErrorOf(custom + "output: {las_version: \"1.2\"}\n");
  EXPECT_NE(err.find("output.las_version = 1.2: LAS 1.2 stores the CRS as GeoTIFF keys"), std::string::npos) << err;
  EXPECT_NE(err.find("use output.las_version 1.4"), std::string::npos) << err;
  EXPECT_NO_THROW(ParseJobConfig("crs: EPSG:2154+5720\ninput: {path: ws}\noutput: {las_version: \"1.2\"}\n",
                                 "job.yaml", "/base"));
}

TEST(JobConfigCrsTest, OriginAndCamerasCrsKeys) {
  const JobConfig c = ParseJobConfig(
      "crs: EPSG:2154+5720\ninput: {path: ws, format: rasters, origin_m: [770000, 6277000, 0.5], "
      "cameras_crs: \"EPSG:4979\"}\n",
      "job.yaml", "/base");
  EXPECT_EQ(c.input.origin_m, (std::vector<double>{770000, 6277000, 0.5}));
  EXPECT_EQ(c.input.cameras_crs, "EPSG:4979");
  EXPECT_EQ(ParseJobConfig("input: {path: ws}\n", "job.yaml", "/base").input.origin_m,
            (std::vector<double>{0, 0, 0}));
  const std::string two = ErrorOf("input: {path: ws, origin_m: [1, 2]}\n");
  EXPECT_NE(two.find("job.yaml:1: input.origin_m = 2 numbers: must be [east, north, height]"), std::string::npos)
      << two;
  const std::string colmap = ErrorOf("crs: EPSG:25832\ninput: {path: ws, cameras_crs: \"EPSG:4979\"}\n");
  EXPECT_NE(colmap.find("input.cameras_crs = EPSG:4979: only read by input.format: rasters"), std::string::npos)
      << colmap;
  const std::string no_crs = ErrorOf("input: {path: ws, format: rasters, cameras_crs: \"EPSG:4979\"}\n");
  EXPECT_NE(no_crs.find("input.cameras_crs = \"EPSG:4979\": positions in another CRS need the project CRS"),
            std::string::npos)
      << no_crs;
  const std::string bad = ErrorOf("crs: EPSG:25832\ninput: {path: ws, format: rasters, cameras_crs: \"EPSG:4978\"}\n");
  EXPECT_NE(bad.find("input.cameras_crs = \"EPSG:4978\": \"WGS 84\" is a geocentric CRS"), std::string::npos) << bad;
  // Both change the points: part of the result settings.
  JobConfig a;
  a.input.path = "ws";
  JobConfig b = a;
  b.input.origin_m = {100.0, 0.0, 0.0};
  EXPECT_NE(ResultSettingsHash(a), ResultSettingsHash(b));
}

TEST(JobConfigCrsTest, PrintDefaultsShowsTheKeyAndItsDoc) {
  const std::string dump = DumpJobConfig(JobConfig{}, true);
  EXPECT_NE(dump.find("\ncrs: \"\"\n"), std::string::npos) << dump;
  EXPECT_NE(dump.find("ENU:lat,lon,h"), std::string::npos);
  JobConfig c;
  c.crs = "EPSG:25832";
  EXPECT_NE(DumpJobConfig(c, false).find("crs: \"EPSG:25832\""), std::string::npos);
}

TEST(JobConfigCrsTest, TheTrueOrthoFollowsTheDsmAndOnWithoutOneIsRefused) {
  JobConfig c;
  c.input.path = "ws";
  EXPECT_FALSE(OrthoWanted(c));  // no CRS: no DSM, no ortho
  c.crs = "EPSG:25832";
  EXPECT_TRUE(OrthoWanted(c));   // auto: with the DSM
  c.output.ortho = "off";
  EXPECT_FALSE(OrthoWanted(c));
  c.output.ortho = "on";
  c.output.dsm = "off";
  try {
    ValidateJobConfig(c);
    ADD_FAILURE() << "output.ortho on without a DSM was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("output.ortho"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("output.dsm"), std::string::npos) << e.what();
  }
  c.output.dsm = "on";
  EXPECT_NO_THROW(ValidateJobConfig(c));
  EXPECT_TRUE(OrthoWanted(c));
}

TEST(JobConfigCrsTest, ChangingTheCrsChangesTheResultSettings) {
  JobConfig a;
  a.input.path = "ws";
  JobConfig b = a;
  b.crs = "EPSG:25832";
  EXPECT_NE(ResultSettingsHash(a), ResultSettingsHash(b));
  const auto changed = ChangedResultSettings(ResultSettingsText(a), ResultSettingsText(b));
  EXPECT_NE(std::find(changed.begin(), changed.end(), "crs \"\" -> \"EPSG:25832\""), changed.end());
  // output.dsm auto: a CRS turns the DSM on, so the DSM's settings change with it; nothing else does.
  for (const std::string& line : changed) {
    if (line.rfind("crs ", 0) != 0) EXPECT_NE(line.find("dsm"), std::string::npos) << line;
  }
}

}  // namespace
}  // namespace sacfuse
