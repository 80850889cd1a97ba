#include "tools/sim/simulate.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/backproject.h"
#include "core/error.h"
#include "io/colmap_workspace.h"
#include "io/geo_mask_io.h"
#include "io/las_reader.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const fs::path& p) { return testing::ReadFileBytes(p); }

nlohmann::json ReadJson(const fs::path& p) { return nlohmann::json::parse(ReadBytes(p)); }

TEST(ValidateSimOptionsTest, PresetsAreValid) {
  for (const std::string& name : SimPresetNames()) EXPECT_NO_THROW(ValidateSimOptions(SimPreset(name))) << name;
  EXPECT_THROW(SimPreset("huge"), ConfigError);
}

TEST(ValidateSimOptionsTest, NamesOptionValueAndRule) {
  SimOptions o = SimPreset("tiny");
  o.gsd_m = -1.0;
  o.errors.scale = -2.0;
  o.errors.dropout_fraction = 0.7;
  o.scene = "mars";
  try {
    ValidateSimOptions(o);
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("sim.gsd_m = -1: must be in [0.005, 10]"), std::string::npos) << m;
    EXPECT_NE(m.find("sim.errors.scale = -2: must be in [0, 100]"), std::string::npos) << m;
    EXPECT_NE(m.find("sim.errors.dropout_fraction = 0.7"), std::string::npos) << m;
    EXPECT_NE(m.find("sim.scene = \"mars\": must be one of {city, las}"), std::string::npos) << m;
  }
  o = SimPreset("tiny");
  o.scene = "las";
  EXPECT_THROW(ValidateSimOptions(o), ConfigError);  // no from_las
}

// One tiny block for all end-to-end checks (about a second).
class TinyBlockTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir();
    options_ = new SimOptions(SimPreset("tiny"));
    options_->write_truth = true;
    summary_ = new SimSummary(SimulateBlock(*options_, dir_->path().string(), [](const std::string& stage, size_t d,
                                                                                 size_t t) { stages_.insert(stage); }));
  }
  static void TearDownTestSuite() {
    delete summary_;
    delete options_;
    delete dir_;
  }
  static fs::path Out() { return dir_->path(); }

  static testing::TempDir* dir_;
  static SimOptions* options_;
  static SimSummary* summary_;
  static std::set<std::string> stages_;
};
testing::TempDir* TinyBlockTest::dir_ = nullptr;
SimOptions* TinyBlockTest::options_ = nullptr;
SimSummary* TinyBlockTest::summary_ = nullptr;
std::set<std::string> TinyBlockTest::stages_;

TEST_F(TinyBlockTest, SummaryAndLayout) {
  EXPECT_EQ(summary_->num_views, 20);
  EXPECT_EQ(summary_->num_nadir + summary_->num_oblique, summary_->num_views);
  EXPECT_GT(summary_->num_nadir, 0);
  EXPECT_GT(summary_->num_oblique, 0);
  EXPECT_GT(summary_->depth_pixels, 0.8 * 20 * 320 * 240);
  EXPECT_GE(summary_->sparse_points, 200u);
  EXPECT_NEAR(static_cast<double>(summary_->reference_points), 60.0 * 60.0 * 10.0, 100.0);
  for (const char* f : {"reference.las", "eval_mask.png", "eval_mask.json", "metadata.json", "sparse/cameras.bin",
                        "sparse/images.bin", "sparse/points3D.bin", "stereo/fusion.cfg", "stereo/patch-match.cfg"}) {
    EXPECT_TRUE(fs::is_regular_file(Out() / f)) << f;
  }
  EXPECT_TRUE(stages_.count("views"));
  EXPECT_TRUE(stages_.count("done"));
}

TEST_F(TinyBlockTest, WorkspaceOpensAndReads) {
  const ColmapWorkspace ws(Out().string(), ColmapDepthType::kGeometric);
  ASSERT_EQ(ws.views().size(), 20u);
  const nlohmann::json meta = ReadJson(Out() / "metadata.json");
  size_t valid = 0, total = 0;
  std::vector<double> dz;
  for (const View& v : ws.views()) {
    EXPECT_EQ(v.camera.width, v.name.rfind("nadir/", 0) == 0 ? 320 : 240) << v.name;
    const DepthMap depth = ws.ReadDepthMap(v);
    const NormalMap normals = ws.ReadNormalMap(v);
    const RgbImage image = ws.ReadImage(v);
    ASSERT_EQ(depth.width, v.camera.width);
    ASSERT_EQ(normals.width, depth.width);
    ASSERT_EQ(image.width, v.camera.width);
    ASSERT_EQ(image.height, v.camera.height);
    const PinholeCamera& cam = v.camera;
    const Rigid3d world_from_cam = v.cam_from_world.Inverse();
    for (int row = 0; row < depth.height; ++row) {
      for (int col = 0; col < depth.width; ++col) {
        const float d = depth.at(row, col);
        const Eigen::Vector3f n(normals.at(row, col, 0), normals.at(row, col, 1), normals.at(row, col, 2));
        ++total;
        if (!IsValidDepth(d)) {
          EXPECT_EQ(n.norm(), 0.0f);
          continue;
        }
        ++valid;
        EXPECT_NEAR(n.norm(), 1.0f, 1e-4f);
        EXPECT_LT(n.cast<double>().dot(cam.Unproject(col + 0.5, row + 0.5, 1.0)), 0.0);  // faces the camera
        if ((row * 31 + col) % 97 == 0) {
          const Eigen::Vector3d p = DepthPixelToWorld(cam, world_from_cam, col, row, d);
          dz.push_back(p.z() - 100.0);
        }
      }
    }
    // The workspace pose is the WRITTEN one of the metadata.
    const auto& jv = meta["views"][v.index];
    EXPECT_EQ(jv["name"], v.name);
    EXPECT_NEAR(jv["written_cam_from_world"]["tx"].get<double>(), v.cam_from_world.translation.x(), 1e-6);
    EXPECT_NEAR(jv["written_cam_from_world"]["qw"].get<double>(), v.cam_from_world.rotation.w(), 1e-9);
  }
  EXPECT_GT(static_cast<double>(valid) / total, 0.85);
  // Points are near the ground level band of the city (terrain +-3 m, buildings and trees up to 45 m).
  std::sort(dz.begin(), dz.end());
  EXPECT_GT(dz[dz.size() / 50], -6.0);
  EXPECT_LT(dz[dz.size() * 49 / 50], 50.0);
}

TEST_F(TinyBlockTest, SparseModelIsConsistent) {
  const ColmapWorkspace ws(Out().string(), ColmapDepthType::kGeometric);
  const ColmapModel& model = ws.model();
  EXPECT_EQ(model.points3D.size(), summary_->sparse_points);
  for (const auto& [id, p] : model.points3D) {
    ASSERT_GE(p.track.size(), 2u);
    for (const ColmapTrackElement& t : p.track) {
      const ColmapImage& image = model.images.at(t.image_id - 1);
      ASSERT_EQ(image.image_id, t.image_id);
      ASSERT_LT(t.point2D_idx, image.points2D.size());
      const ColmapPoint2D& kp = image.points2D[t.point2D_idx];
      EXPECT_EQ(kp.point3D_id, id);
      // Reprojection with the written pose: only the keypoint noise (0.5 px sigma) remains.
      const View& v = ws.views()[t.image_id - 1];
      const Eigen::Vector2d uv = v.camera.Project(v.cam_from_world * p.xyz);
      EXPECT_LT((uv - kp.xy).norm(), 3.0);
    }
  }
}

TEST_F(TinyBlockTest, ReferenceMaskAndMetadata) {
  LasHeader header;
  const std::vector<LasPoint> ref = ReadAllLasPoints((Out() / "reference.las").string(), &header);
  EXPECT_EQ(header.version_minor, 4);
  ASSERT_EQ(ref.size(), summary_->reference_points);
  std::set<int> classes;
  for (const LasPoint& p : ref) {
    classes.insert(p.classification);
    EXPECT_GE(p.xyz.x(), options_->origin_east_m);
    EXPECT_LE(p.xyz.x(), options_->origin_east_m + options_->area_width_m);
  }
  for (int c : classes) EXPECT_TRUE(c == 2 || c == 5 || c == 6) << c;
  EXPECT_TRUE(classes.count(2));

  const GeoMask mask = ReadGeoMask((Out() / "eval_mask.png").string());
  EXPECT_NEAR(mask.origin_x, options_->origin_east_m, 1e-9);
  EXPECT_NEAR(mask.origin_y, options_->origin_north_m + options_->area_height_m, 1e-9);
  EXPECT_DOUBLE_EQ(mask.cell_size_m, 0.5);
  size_t n_inside = 0;
  for (uint8_t c : mask.cells) n_inside += c != 0;
  EXPECT_GE(static_cast<double>(n_inside) / mask.cells.size(), 0.5);

  const nlohmann::json meta = ReadJson(Out() / "metadata.json");
  EXPECT_EQ(meta["preset"], "tiny");
  EXPECT_EQ(meta["seed"], 1);
  EXPECT_EQ(meta["crs"], options_->crs);
  EXPECT_EQ(meta["options"]["errors"]["scale"], 1.0);
  EXPECT_EQ(meta["views"].size(), 20u);
  const auto& v0 = meta["views"][0];
  for (const char* key : {"name", "kind", "camera", "true_cam_from_world", "written_cam_from_world", "true_center",
                          "written_center", "errors", "files"}) {
    EXPECT_TRUE(v0.contains(key)) << key;
  }
  // written centre = true centre + recorded delta.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(v0["written_center"][k].get<double>(),
                v0["true_center"][k].get<double>() + v0["errors"]["pose_center_delta_m"][k].get<double>(), 1e-6);
  }
}

TEST_F(TinyBlockTest, TruthWorkspaceHasTruePosesAndExactDepth) {
  const ColmapWorkspace truth((Out() / "truth").string(), ColmapDepthType::kGeometric);
  const ColmapWorkspace main(Out().string(), ColmapDepthType::kGeometric);
  ASSERT_EQ(truth.views().size(), 20u);
  const nlohmann::json meta = ReadJson(Out() / "metadata.json");
  for (const View& v : truth.views()) {
    EXPECT_NEAR(meta["views"][v.index]["true_cam_from_world"]["tz"].get<double>(), v.cam_from_world.translation.z(),
                1e-6);
    EXPECT_TRUE(fs::is_symlink(truth.ImagePath(v)));
    EXPECT_TRUE(truth.ReadImage(v).data == main.ReadImage(main.views()[v.index]).data);
    EXPECT_FALSE(truth.ReadDepthMap(v).data == main.ReadDepthMap(main.views()[v.index]).data);
  }
}

SimOptions FewViews(uint64_t seed) {
  SimOptions o = SimPreset("tiny");
  o.seed = seed;
  o.max_nadir_views = 1;
  o.max_oblique_views = 2;
  o.reference_density_pts_m2 = 1.0;
  return o;
}

std::vector<std::string> DepthFiles(const fs::path& root) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root / "stereo/depth_maps")) {
    if (e.is_regular_file()) files.push_back(fs::relative(e.path(), root).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(SimulateDeterminismTest, SameSeedSameBytesOtherSeedDiffers) {
  testing::TempDir a, b, c;
  SimulateBlock(FewViews(5), a.path().string());
  SimulateBlock(FewViews(5), b.path().string());
  SimulateBlock(FewViews(6), c.path().string());
  const std::vector<std::string> files = DepthFiles(a.path());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files, DepthFiles(b.path()));
  for (const std::string& f : files) {
    EXPECT_TRUE(ReadBytes(a.path() / f) == ReadBytes(b.path() / f)) << f;
  }
  for (const char* f : {"sparse/images.bin", "sparse/points3D.bin", "reference.las", "eval_mask.png"}) {
    EXPECT_TRUE(ReadBytes(a.path() / f) == ReadBytes(b.path() / f)) << f;
  }
  bool differs = false;
  for (const std::string& f : DepthFiles(c.path())) {
    differs |= !fs::exists(a.path() / f) || ReadBytes(a.path() / f) != ReadBytes(c.path() / f);
  }
  EXPECT_TRUE(differs);
}

TEST(SimulateNoErrorsTest, DepthEqualsTruthAndPosesAreTrue) {
  testing::TempDir dir;
  SimOptions o = FewViews(3);
  o.errors.enabled = false;
  o.write_truth = true;
  SimulateBlock(o, dir.path().string());
  for (const std::string& f : DepthFiles(dir.path())) {
    EXPECT_TRUE(ReadBytes(dir.path() / f) == ReadBytes(dir.path() / "truth" / f)) << f;
  }
  EXPECT_TRUE(ReadBytes(dir.path() / "sparse/images.bin") == ReadBytes(dir.path() / "truth/sparse/images.bin"));
}

}  // namespace
}  // namespace sacfuse
