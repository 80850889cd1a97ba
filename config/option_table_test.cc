// The one table of options (config/option_table.h): every key documented with a unit and a range or choices,
// range errors as structured {key, value, rule}, only the keys of the method in use checked, fusion.method parsed
// into its enum from one name table, and the result-affecting settings read from the table's flag.
#include "config/option_table.h"

#include <limits>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "config/config_test_util.h"
#include "config/job_config.h"
#include "config/result_settings.h"
#include "core/error.h"

namespace sacfuse {
namespace {

bool Contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(OptionTableTest, EveryKeyOnceWithDocUnitAndRangeOrChoices) {
  const std::vector<OptionRow> rows = JobOptionRows(JobConfig());
  std::set<std::string> keys, free_text;
  for (const OptionRow& row : rows) {
    EXPECT_TRUE(keys.insert(row.key).second) << row.key << " twice";
    EXPECT_FALSE(row.doc.empty()) << row.key;
    EXPECT_FALSE(row.spec.unit.empty()) << row.key << ": unit or \"-\"";
    const OptionRange& r = row.spec.range;
    if (row.type == "number" || row.type == "whole number" || row.type == "list of numbers") {
      EXPECT_FALSE(r.is_text) << row.key;
      EXPECT_LT(r.min, r.max) << row.key;
      EXPECT_GE(r.min, -kMaxConfigMagnitude) << row.key;
      EXPECT_LE(r.max, kMaxConfigMagnitude) << row.key;
    } else if (row.type == "choice" || row.type == "true or false") {
      EXPECT_FALSE(r.choices.empty()) << row.key;
      EXPECT_NE(r.Rule().find("must be one of {"), std::string::npos) << row.key;
    } else {
      ASSERT_EQ(row.type, "text") << row.key;
      EXPECT_TRUE(r.is_text && r.choices.empty()) << row.key;
      free_text.insert(row.key);
    }
  }
  // Free text only for paths and the CRSs (their form is a rule of its own in config/job_config.cc).
  EXPECT_EQ(free_text, (std::set<std::string>{"crs", "input.path", "input.cameras", "input.cameras_crs",
                                                "output.dir", "fusion.superpixel_cache_dir", "evaluation.reference",
                                                "evaluation.mask"}));
  // The values of the default config are the structs' defaults, as JobConfigValues and --print-defaults show them.
  const auto values = JobConfigValues(JobConfig());
  ASSERT_EQ(values.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].value, values[i].second) << rows[i].key;
}

TEST(OptionTableTest, RangeRulesReadLikeTheMessages) {
  EXPECT_EQ(Above(0).Rule(), "must be > 0");
  EXPECT_EQ(AtLeast(1).Rule(), "must be >= 1");
  EXPECT_EQ(Closed(1e-6, 1.0).Rule(), "must be in [1e-06, 1]");
  EXPECT_EQ(OpenClosed(0, 0.5).Rule(), "must be in (0, 0.5]");
  EXPECT_EQ(AnyNumber().Rule(), "must be a finite number in [-1e9, 1e9]");
  EXPECT_EQ(Choices({"a", "b"}).Rule(), "must be one of {a, b}");
  EXPECT_TRUE(OpenClosed(0, 0.5).Contains(0.5));
  EXPECT_FALSE(OpenClosed(0, 0.5).Contains(0.0));
  EXPECT_FALSE(Above(0).Contains(1e300));
  EXPECT_FALSE(AtLeast(0).Contains(std::numeric_limits<double>::quiet_NaN()));
}

TEST(OptionTableTest, RangeErrorsAreStructured) {
  JobConfig c;
  c.fusion.sac.tau_m = 0;
  c.fusion.sac.max_neighbor_views = 65;
  c.evaluation.tau_gsd = {2, -1};
  const std::vector<OptionError> errors = MakeOptionTable(&c).Check(MethodScope(FusionMethodKind::kSac));
  ASSERT_EQ(errors.size(), 4u);  // and input.path: required
  EXPECT_EQ(errors[0].key, "input.path");
  EXPECT_EQ(errors[0].value, "");
  EXPECT_EQ(errors[0].rule, "a value is required");
  EXPECT_EQ(errors[1].key, "fusion.max_neighbor_views");
  EXPECT_EQ(errors[1].value, "65");
  EXPECT_EQ(errors[1].rule, "must be in [1, 64]");
  EXPECT_EQ(errors[2].key, "fusion.tau_m");
  EXPECT_EQ(errors[2].rule, "must be > 0");
  EXPECT_EQ(errors[3].key, "evaluation.tau_gsd");
  EXPECT_EQ(errors[3].value, "-1");
  EXPECT_EQ(errors[3].rule, "each item must be > 0");
  // Formatted once, in the style of every config message.
  EXPECT_EQ(FormatOptionError(errors[2]), "fusion.tau_m = 0: must be > 0");
  EXPECT_EQ(FormatOptionError(errors[0]), "input.path is empty: a value is required");
  EXPECT_EQ(OptionErrorsMessage({errors[2]}, "job.yaml", {{"fusion.tau_m", "job.yaml:7: "}}),
            "job.yaml: invalid configuration\n  job.yaml:7: fusion.tau_m = 0: must be > 0");
  // Configs built in code reach the same rules through ValidateJobConfig.
  c.input.path = "/ws";
  try {
    ValidateJobConfig(c);
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(Contains(e.what(), "config: invalid configuration\n  fusion.max_neighbor_views = 65: must be in"))
        << e.what();
  }
}

// Each method's keys are checked only when it runs; the neighbour-view keys for the methods that reproject.
TEST(OptionTableTest, KeysOfAnotherMethodAreNotValidated) {
  const std::string tsdf = "tsdf:\n  voxel_size_gsd: -1\n  min_weight: 0\n";
  EXPECT_EQ(ConfigErrorOf("input: {path: ws}\nfusion: {method: sac}\n" + tsdf), "");
  const std::string err = ConfigErrorOf("input: {path: ws}\nfusion: {method: tsdf}\n" + tsdf);
  EXPECT_TRUE(Contains(err, "job.yaml:4: tsdf.voxel_size_gsd = -1: must be > 0")) << err;
  EXPECT_TRUE(Contains(err, "job.yaml:5: tsdf.min_weight = 0: must be >= 1")) << err;
  // SAC's own keys and superpixels: not read by the other methods.
  const std::string sac = "fusion:\n  method: METHOD\n  tau_m: 0\n  combine_max_views: 0\nsuperpixels: {ruler: 0}\n";
  for (const char* method : {"union", "consistency", "disparity_normal", "tsdf", "multiray"}) {
    std::string yaml = "input: {path: ws}\n" + sac;
    yaml.replace(yaml.find("METHOD"), 6, method);
    EXPECT_EQ(ConfigErrorOf(yaml), "") << method;
  }
  const std::string refused = ConfigErrorOf("input: {path: ws}\nfusion:\n  method: sac\n  tau_m: 0\n"
                                            "  combine_max_views: 0\nsuperpixels: {ruler: 0}\n");
  EXPECT_TRUE(Contains(refused, "job.yaml:4: fusion.tau_m = 0: must be > 0")) << refused;
  EXPECT_TRUE(Contains(refused, "job.yaml:5: fusion.combine_max_views = 0: must be in [1, 64]")) << refused;
  EXPECT_TRUE(Contains(refused, "job.yaml:6: superpixels.ruler = 0: must be > 0")) << refused;
  // Neighbour views: read by sac, consistency, disparity_normal and multiray; not by union and tsdf.
  for (const char* method : {"sac", "consistency", "disparity_normal", "multiray"}) {
    const std::string e = ConfigErrorOf(std::string("input: {path: ws}\nfusion: {method: ") + method +
                                        ", max_view_angle_deg: 200}\n");
    EXPECT_TRUE(Contains(e, "fusion.max_view_angle_deg = 200: must be in [0, 180]")) << method << e;
  }
  for (const char* method : {"union", "tsdf"}) {
    EXPECT_EQ(ConfigErrorOf(std::string("input: {path: ws}\nfusion: {method: ") + method +
                            ", max_view_angle_deg: 200, min_footprint_overlap: 2}\n"),
              "")
        << method;
  }
}

// The rules core's invariants name by field (core/*_test.cc) reach the user by YAML key, value, rule and line.
TEST(OptionTableTest, MethodRulesNameTheYamlKeys) {
  std::string err = ConfigErrorOf(
      "input: {path: ws}\nfusion: {method: disparity_normal}\ndisparity_normal:\n  disparity_threshold_px: -1\n"
      "  normal_threshold_deg: 200\n  min_consistent_views: 0\n  normal_radius_px: 0\n");
  for (const char* part : {"job.yaml:4: disparity_normal.disparity_threshold_px = -1: must be > 0",
                           "job.yaml:5: disparity_normal.normal_threshold_deg = 200: must be in (0, 180]",
                           "job.yaml:6: disparity_normal.min_consistent_views = 0: must be in [1, 64]",
                           "job.yaml:7: disparity_normal.normal_radius_px = 0: must be in [1, 10]"}) {
    EXPECT_TRUE(Contains(err, part)) << part << "\n" << err;
  }
  err = ConfigErrorOf("input: {path: ws}\nsuperpixels:\n  region_size_px: 1\n  ruler: 0\n  iterations: 0\n"
                      "  depth_weight: -1\n");
  for (const char* part : {"job.yaml:3: superpixels.region_size_px = 1: must be in [2, 128]",
                           "job.yaml:4: superpixels.ruler = 0: must be > 0",
                           "job.yaml:5: superpixels.iterations = 0: must be in [1, 100]",
                           "job.yaml:6: superpixels.depth_weight = -1: must be >= 0"}) {
    EXPECT_TRUE(Contains(err, part)) << part << "\n" << err;
  }
  err = ConfigErrorOf("input: {path: ws}\nsuperpixels: {block_size_px: 20}\n");
  EXPECT_TRUE(Contains(err, "job.yaml:2: superpixels.block_size_px = 20: must be >= 2 * superpixels.region_size_px "
                            "(32)"))
      << err;
  err = ConfigErrorOf("input: {path: ws}\nfusion: {method: multiray}\nmultiray: {min_rays: 1, depth_sigma_gsd: -1}\n");
  EXPECT_TRUE(Contains(err, "job.yaml:3: multiray.min_rays = 1: must be in [2, 65]")) << err;
  EXPECT_TRUE(Contains(err, "job.yaml:3: multiray.depth_sigma_gsd = -1: must be >= 0")) << err;
  err = ConfigErrorOf("input: {path: ws}\nfusion: {method: consistency}\nconsistency: {depth_threshold_rel: 0}\n");
  EXPECT_TRUE(Contains(err, "job.yaml:3: consistency.depth_threshold_rel = 0: must be in (0, 0.5]")) << err;
  err = ConfigErrorOf("input: {path: ws}\ntiling:\n  z_min_m: 5\n  z_max_m: 5\n  claim_timeout_s: 0\n");
  EXPECT_TRUE(Contains(err, "job.yaml:4: tiling.z_max_m = 5: must be > tiling.z_min_m (5)")) << err;
  EXPECT_TRUE(Contains(err, "job.yaml:5: tiling.claim_timeout_s = 0: must be > 0")) << err;
}

TEST(OptionTableTest, FusionMethodIsParsedOnceFromOneNameTable) {
  EXPECT_EQ(FusionMethodNameList(),
            (std::vector<std::string>{"sac", "union", "consistency", "disparity_normal", "tsdf", "multiray"}));
  for (const FusionMethodName& m : FusionMethodNames()) {
    EXPECT_EQ(FusionMethodFromName(m.name), m.kind);
    EXPECT_EQ(NameOf(m.kind), m.name);
    const JobConfig c = ParseJobConfig(std::string("input: {path: ws}\nfusion: {method: ") + m.name + "}\n",
                                       "job.yaml", "/base");
    EXPECT_EQ(c.fusion.method, m.kind);
    EXPECT_TRUE(Contains(DumpJobConfig(c, false), std::string("  method: \"") + m.name + "\"\n"));
  }
  EXPECT_FALSE(FusionMethodFromName("tsfd").has_value());
  for (const OptionRow& row : JobOptionRows(JobConfig())) {
    if (row.key == "fusion.method") {
      EXPECT_EQ(row.spec.range.choices, FusionMethodNameList());
    }
  }
}

// The resume hash of existing runs must not change unless a change of the points is meant: the text main wrote
// before the table (captured from its --print-defaults and its prefix list) for the default config, with the keys
// added since.
TEST(OptionTableTest, ResultSettingsTextOfTheDefaultConfigIsUnchanged) {
  const std::string expected =
      "crs: \"\"\ninput.format: \"colmap\"\ninput.path: \"\"\ninput.depth_type: \"geometric\"\ninput.cameras: \"\"\n"
      "input.depth_kind: \"z\"\ninput.origin_m: [0.0, 0.0, 0.0]\ninput.cameras_crs: \"\"\n"
      "output.las_version: \"1.4\"\noutput.scale_m: 0.001\n"
      // coregistration.* (twentieth session): a new stage that changes the points, so tiled runs of older
      // versions are recomputed, not resumed.
      "coregistration.enabled: true\ncoregistration.max_pixels_per_view: 250000\n"
      "coregistration.samples_per_view: 2000\ncoregistration.iterations: 20\n"
      "coregistration.max_neighbor_views: 12\ncoregistration.max_view_angle_deg: 65.0\n"
      "coregistration.huber_gsd: 1.2\ncoregistration.max_residual_gsd: 8.0\nfusion.method: \"sac\"\n"
      "fusion.max_neighbor_views: 10\nfusion.max_view_angle_deg: 65.0\nfusion.min_footprint_overlap: 0.05\n"
      "fusion.correspondence: \"reprojection\"\nfusion.depth_tolerance_gsd: 3.0\nfusion.depth_tolerance_rel: 0.0\n"
      "fusion.proximity_radius_m: 0.0\nfusion.tau_m: 2.0\nfusion.netlets: \"node\"\nfusion.unary: \"quality\"\n"
      "fusion.quality_weight: 1.0\nfusion.min_incidence_cos: 0.2\nfusion.agreement_weight: 1.0\n"
      "fusion.agreement_tolerance_gsd: 1.5\nfusion.displacement_weight: 0.5\nfusion.smoothness_weight: 0.0\n"
      "fusion.smoothness_rounds: 2\nfusion.collapse: \"best_view\"\nfusion.redundancy_tolerance_sigmas: 3.0\n"
      "fusion.free_space_min_views: 2\nfusion.free_space_sigmas: 3.0\nfusion.free_space_early_pass_views: 16\n"
      "fusion.free_space_window_px: 1\n"
      "fusion.free_space_edge_band_px: 2\nfusion.depth_edge_jump_gsd: 8.0\nfusion.min_consistent_views: 4\n"
      "fusion.outlier_expected_factor: 1.5\nfusion.weak_support_min_views: 0\nfusion.weak_support_rim_px: 2\n"
      "fusion.independent_support: false\n"
      "fusion.correspondence_tolerance_sigmas: 1.0\n"
      "fusion.coverage_tolerance_sigmas: 5.0\nfusion.combine: \"average\"\nfusion.combine_gate_gsd: 4.0\n"
      "fusion.combine_gate_sigmas: 3.0\nfusion.combine_slope_step_sigmas: 3.0\nfusion.combine_weights: \"view\"\n"
      "fusion.combine_surface: \"plane\"\nfusion.combine_passes: 2\nfusion.combine_later_pass_gate: 1.0\n"
      "fusion.combine_later_pass_min_shift_gsd: 1.0\nfusion.combine_anchors: true\nfusion.combine_max_views: 40\n"
      "fusion.combine_max_view_angle_deg: 65.0\nfusion.combine_region_m: 128.0\n"
      "superpixels.region_size_px: 16\nsuperpixels.ruler: 10.0\nsuperpixels.iterations: 4\n"
      "superpixels.algorithm: \"fast\"\nsuperpixels.block_size_px: 1024\nsuperpixels.depth_weight: 0.0\n"
      "consistency.depth_threshold_rel: 0.01\ndisparity_normal.disparity_threshold_px: 0.5\n"
      "disparity_normal.normal_threshold_deg: 30.0\ndisparity_normal.min_consistent_views: 2\n"
      "disparity_normal.normal_radius_px: 2\ntsdf.voxel_size_gsd: 1.0\ntsdf.truncation_gsd: 8.0\n"
      "tsdf.min_weight: 2.0\ntsdf.max_memory_gb: 0.0\nmultiray.depth_tolerance_gsd: 3.0\nmultiray.min_rays: 2\n"
      "multiray.ray_sigma_px: 0.29\nmultiray.depth_sigma_gsd: 2.0\ntiling.tile_size_m: 0.0\ntiling.halo_m: 5.0\n"
      "tiling.window_margin_px: 16\ntiling.z_min_m: 0.0\ntiling.z_max_m: 100.0\n";
  EXPECT_EQ(ResultSettingsText(JobConfig()), expected);
  // Keys that only say where files go, how to run or how to score stay out of it.
  JobConfig other;
  other.output.dir = "elsewhere";
  other.output.format = "las";
  other.fusion.superpixel_cache_dir = "/cache";
  other.tiling.claim_timeout_s = 60;
  other.resources.threads = 3;
  other.evaluation.gsd_m = 0.2;
  other.log.level = "debug";
  EXPECT_EQ(ResultSettingsText(other), expected);
}

// Issue 50: --print-defaults said tile files stay uncompressed LAS; they are LAZ (tiles/tile_marker.h).
TEST(OptionTableTest, PrintDefaultsSaysTilesAreLaz) {
  const std::string text = DumpJobConfig(JobConfig(), true);
  EXPECT_EQ(text.find("uncompressed LAS (intermediate"), std::string::npos) << text;
  EXPECT_NE(text.find("Tiled runs write their tiles as LAZ (tiles/<id>.laz)"), std::string::npos)
      << text;
}

}  // namespace
}  // namespace sacfuse
