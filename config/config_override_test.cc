// Command-line overrides of config keys (--set KEY=VALUE, --output-dir DIR): applied after the file and before
// validation, every value type read as YAML, errors that name the option like a file names its line, paths relative
// to the current directory, and a result exactly like the same key in the file (values, effective YAML, resume hash).
#include "config/config_override.h"

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "config/job_config.h"
#include "config/result_settings.h"
#include "config/version.h"
#include "core/error.h"

namespace sacfuse {
namespace {

const char* kFile = "input: {path: ws}\noutput: {dir: out}\nfusion:\n  tau_m: 2.0\n";

ConfigOverride Set(const std::string& text) { return ParseSetOption(text); }

JobConfig WithSets(const std::vector<std::string>& sets, const std::string& yaml = kFile) {
  std::vector<ConfigOverride> overrides;
  for (const std::string& s : sets) overrides.push_back(Set(s));
  return ParseJobConfig(yaml, "job.yaml", "/base", overrides);
}

std::string ErrorOf(const std::vector<std::string>& sets, const std::string& yaml = kFile) {
  try {
    WithSets(sets, yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigOverrideTest, SplitsAtTheFirstEquals) {
  const ConfigOverride o = Set("crs=ENU:47.1,8.5,400=x");
  EXPECT_EQ(o.key, "crs");
  EXPECT_EQ(o.value, "ENU:47.1,8.5,400=x");
  EXPECT_EQ(o.Describe(), "--set crs=ENU:47.1,8.5,400=x");
  EXPECT_EQ(Set(" fusion.tau_m =1").key, "fusion.tau_m");
  EXPECT_THROW(Set("fusion.tau_m"), ConfigError);
  EXPECT_THROW(Set("=1"), ConfigError);
  try {
    Set("fusion.tau_m:1");
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--set fusion.tau_m:1: expected KEY=VALUE"), std::string::npos) << e.what();
  }
}

TEST(ConfigOverrideTest, EveryValueTypeIsReadAsYaml) {
  const JobConfig c = WithSets({"fusion.tau_m=1.5", "superpixels.region_size_px=12", "coregistration.enabled=false",
                                "fusion.method=union", "evaluation.tau_gsd=[1, 2.5]", "crs=EPSG:25832",
                                "output.las_version=\"1.2\"", "input.depth_type=photometric", "superpixels.ruler=7"});
  EXPECT_DOUBLE_EQ(c.fusion.sac.tau_m, 1.5);
  EXPECT_EQ(c.fusion.sac.superpixels.region_size_px, 12);
  EXPECT_FALSE(c.coregistration.enabled);
  EXPECT_EQ(c.fusion.method, FusionMethodKind::kUnion);
  EXPECT_EQ(c.evaluation.tau_gsd, (std::vector<double>{1.0, 2.5}));
  EXPECT_EQ(c.crs, "EPSG:25832");
  EXPECT_EQ(c.output.las_version, "1.2");
  EXPECT_EQ(c.input.depth_type, "photometric");
  EXPECT_FLOAT_EQ(c.fusion.sac.superpixels.ruler, 7.0f);
  // A quoted YAML string and an empty value (the empty string, as `mask: ""` in a file).
  EXPECT_EQ(WithSets({"crs='EPSG:32632'"}).crs, "EPSG:32632");
  EXPECT_EQ(WithSets({"evaluation.mask="}, std::string(kFile) + "evaluation: {mask: m.png}\n").evaluation.mask, "");
}

TEST(ConfigOverrideTest, OverridesWinOverTheFileAndLaterOnesWin) {
  EXPECT_DOUBLE_EQ(WithSets({}).fusion.sac.tau_m, 2.0);
  EXPECT_DOUBLE_EQ(WithSets({"fusion.tau_m=3"}).fusion.sac.tau_m, 3.0);
  EXPECT_DOUBLE_EQ(WithSets({"fusion.tau_m=3", "fusion.tau_m=4"}).fusion.sac.tau_m, 4.0);
  // A key the file does not have, in a section the file does not have.
  EXPECT_EQ(WithSets({"tiling.halo_m=7"}).tiling.halo_m, 7.0);
  // The file alone may be incomplete: the override supplies the required key.
  EXPECT_EQ(WithSets({"input.path=/data/ws"}, "").input.path, "/data/ws");
}

TEST(ConfigOverrideTest, ErrorsNameTheOptionLikeTheFileNamesItsLine) {
  const std::string type = ErrorOf({"fusion.tau_m=abc"});
  EXPECT_NE(type.find("job.yaml: invalid configuration"), std::string::npos) << type;
  EXPECT_NE(type.find("  --set fusion.tau_m: expected a number, got \"abc\""), std::string::npos) << type;
  const std::string range = ErrorOf({"fusion.tau_m=-1", "resources.memory_gb=0"});
  EXPECT_NE(range.find("  --set fusion.tau_m = -1: must be > 0"), std::string::npos) << range;
  EXPECT_NE(range.find("  --set resources.memory_gb = 0: must be > 0"), std::string::npos) << range;
  const std::string choice = ErrorOf({"fusion.method=magic"});
  EXPECT_NE(choice.find("--set fusion.method: \"magic\" is not one of {sac, union"), std::string::npos) << choice;
  const std::string unknown = ErrorOf({"fusion.tua_m=1"});
  EXPECT_NE(unknown.find("--set fusion.tua_m: unknown key; allowed in fusion: "), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("tau_m"), std::string::npos) << unknown;
  const std::string top = ErrorOf({"fusoin.tau_m=1"});
  EXPECT_NE(top.find("--set fusoin.tau_m: unknown key; allowed at the top level: "), std::string::npos) << top;
  const std::string section = ErrorOf({"fusion=1"});
  EXPECT_NE(section.find("--set fusion: a section, not a key"), std::string::npos) << section;
  const std::string yaml = ErrorOf({"evaluation.tau_gsd=[1, 2"});
  EXPECT_NE(yaml.find("--set evaluation.tau_gsd: \"[1, 2\" is not valid YAML"), std::string::npos) << yaml;
  // A cross-key rule broken by an override names the option too, and the file's own errors keep their lines.
  const std::string cross = ErrorOf({"tiling.z_max_m=-5"}, std::string(kFile) + "tiling: {z_min_m: 0}\n");
  EXPECT_NE(cross.find("--set tiling.z_max_m = -5: must be > tiling.z_min_m (0)"), std::string::npos) << cross;
  const std::string both = ErrorOf({"fusion.tau_m=0"}, std::string(kFile) + "resources: {memory_gb: -1}\n");
  EXPECT_NE(both.find("job.yaml:5: resources.memory_gb = -1: must be > 0"), std::string::npos) << both;
  EXPECT_NE(both.find("--set fusion.tau_m = 0: must be > 0"), std::string::npos) << both;
}

TEST(ConfigOverrideTest, PathsAreRelativeToTheCurrentDirectoryAndOutputDirIsLiteral) {
  const std::string cwd = std::filesystem::current_path().string();
  const JobConfig c = WithSets({"input.path=blocks/ws", "evaluation.reference=/abs/ref.las"});
  EXPECT_EQ(c.input.path, cwd + "/blocks/ws");
  EXPECT_EQ(c.output.dir, "/base/out");  // from the file: relative to the file's folder
  EXPECT_EQ(c.evaluation.reference, "/abs/ref.las");
  // --output-dir: a path, never read as YAML ("yes" would be true, "[a]" a list).
  for (const std::string dir : {"yes", "[a]", "out #2"}) {
    const JobConfig o =
        ParseJobConfig(kFile, "job.yaml", "/base", {ConfigOverride{"output.dir", dir, true, "--output-dir"}});
    EXPECT_EQ(o.output.dir, cwd + "/" + dir);
  }
  const std::string empty = [] {
    try {
      ParseJobConfig(kFile, "job.yaml", "/base", {ConfigOverride{"output.dir", "", true, "--output-dir"}});
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(empty.find("--output-dir output.dir is empty: a value is required"), std::string::npos) << empty;
}

TEST(ConfigOverrideTest, ResultIsExactlyTheSameKeyInTheFile) {
  const JobConfig in_file = ParseJobConfig(
      "input: {path: ws}\noutput: {dir: out}\nfusion:\n  tau_m: 1.25\nsuperpixels: {algorithm: slic}\n", "job.yaml",
      "/base");
  const JobConfig overridden = WithSets({"fusion.tau_m=1.25", "superpixels.algorithm=slic"});
  EXPECT_EQ(ResultSettingsText(overridden), ResultSettingsText(in_file));
  EXPECT_EQ(ResultSettingsHash(overridden), ResultSettingsHash(in_file));
  EXPECT_NE(ResultSettingsHash(overridden), ResultSettingsHash(WithSets({})));
  EXPECT_EQ(DumpJobConfig(overridden, false), DumpJobConfig(in_file, false));
  // The effective YAML names the version, the file and the overrides in its header.
  const std::string effective = DumpJobConfig(overridden, true);
  EXPECT_EQ(effective.rfind("# sacfuse run configuration, written by " + FullVersionString() + ".\n", 0), 0u)
      << effective;
  EXPECT_NE(effective.find("# The configuration of job.yaml with --set fusion.tau_m=1.25 --set "
                           "superpixels.algorithm=slic, every key as a run uses it.\n"),
            std::string::npos)
      << effective;
}

// A line break in an override cannot end the header's comment line and smuggle a key into the effective YAML.
TEST(ConfigOverrideTest, LineBreaksInTheHeaderStayInsideTheComment) {
  JobConfig c;
  c.input.path = "/ws";
  c.source_file = "job.yaml";
  c.overrides = {ConfigOverride{"log.level", "info\ntiling: {halo_m: 99}", false, "--set"}};
  const std::string text = DumpJobConfig(c, true);
  EXPECT_NE(text.find("--set log.level=info\\ntiling: {halo_m: 99}"), std::string::npos) << text;
  const JobConfig back = ParseJobConfig(text, "effective.yaml", "");
  EXPECT_DOUBLE_EQ(back.tiling.halo_m, JobConfig().tiling.halo_m);
}

}  // namespace
}  // namespace sacfuse
