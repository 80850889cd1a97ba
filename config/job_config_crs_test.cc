// The top-level `crs` key: parsed, validated at load with a message naming the key, value and rule, shown by
// --print-defaults, and part of the result-affecting settings (a changed CRS recomputes tiles).
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
  for (const std::string crs : {"EPSG:25832", "EPSG:32633", "EPSG:32733", "ENU:51.5,7.46,120", ""}) {
    const JobConfig c = ParseJobConfig("crs: \"" + crs + "\"\ninput: {path: ws}\n", "job.yaml", "/base");
    EXPECT_EQ(c.crs, crs);
  }
}

TEST(JobConfigCrsTest, RejectsOthersNamingKeyLineValueAndWhatIsSupported) {
  const std::string err = ErrorOf("input: {path: ws}\ncrs: EPSG:4326\n");
  EXPECT_NE(err.find("job.yaml:2: crs = \"EPSG:4326\": EPSG code 4326 is not one of the supported"), std::string::npos)
      << err;
  EXPECT_NE(err.find("EPSG:258zz"), std::string::npos) << err;
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
  c.crs = "EPSG:25839";
  EXPECT_THROW(ValidateJobConfig(c), ConfigError);
}

TEST(JobConfigCrsTest, PrintDefaultsShowsTheKeyAndItsDoc) {
  const std::string dump = DumpJobConfig(JobConfig{}, true);
  EXPECT_NE(dump.find("\ncrs: \"\"\n"), std::string::npos) << dump;
  EXPECT_NE(dump.find("ENU:lat,lon,h"), std::string::npos);
  JobConfig c;
  c.crs = "EPSG:25832";
  EXPECT_NE(DumpJobConfig(c, false).find("crs: \"EPSG:25832\""), std::string::npos);
}

TEST(JobConfigCrsTest, ChangingTheCrsChangesTheResultSettings) {
  JobConfig a;
  a.input.path = "ws";
  JobConfig b = a;
  b.crs = "EPSG:25832";
  EXPECT_NE(ResultSettingsHash(a), ResultSettingsHash(b));
  const auto changed = ChangedResultSettings(ResultSettingsText(a), ResultSettingsText(b));
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_EQ(changed[0], "crs \"\" -> \"EPSG:25832\"");
}

}  // namespace
}  // namespace sacfuse
