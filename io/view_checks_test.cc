// Every camera pose and intrinsic is checked when an input is opened, one rule for all formats (issue 14: a NaN,
// inf or 1e300 camera translation silently dropped that view). Each error names the view and the file.
#include "io/view_checks.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/colmap_model.h"
#include "io/colmap_workspace.h"
#include "io/openmvs_block.h"
#include "io/openmvs_dmap.h"
#include "io/raster_block.h"
#include "tests/support/error_of.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::InputErrorOf;
using sacfuse::testing::TempDir;

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::nan("");

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A one-image COLMAP model: PINHOLE 640x480, f 500, camera 100 m above the origin looking down.
ColmapModel OneImageModel(const Eigen::Vector3d& translation, double focal = 500.0) {
  ColmapModel m;
  ColmapCamera cam;
  cam.camera_id = 1;
  cam.model = "PINHOLE";
  cam.width = 640;
  cam.height = 480;
  cam.params = {focal, focal, 320.0, 240.0};
  m.cameras[1] = cam;
  ColmapImage img;
  img.image_id = 7;
  img.camera_id = 1;
  img.name = "nadir.jpg";
  img.cam_from_world_rotation = Eigen::Quaterniond(0, 1, 0, 0);
  img.cam_from_world_translation = translation;
  m.images.push_back(img);
  return m;
}

// The model, and a depth map file for each image (only its presence counts: the workspace reads no depth here).
void WriteModel(const ColmapModel& model, bool binary, const TempDir& dir) {
  fs::create_directories(dir / "sparse");
  if (binary) {
    WriteColmapModelBinary(model, (dir / "sparse").string());
  } else {
    WriteColmapModelText(model, (dir / "sparse").string());
  }
  fs::create_directories(dir / "stereo/depth_maps");
  for (const ColmapImage& img : model.images) std::ofstream(dir / "stereo/depth_maps" / (img.name + ".geometric.bin"));
}

std::string WorkspaceError(const ColmapModel& model, bool binary) {
  TempDir dir;
  WriteModel(model, binary, dir);
  return InputErrorOf([&] { ColmapWorkspace ws(dir.path().string(), ColmapDepthType::kGeometric); });
}

TEST(ViewChecksTest, ColmapTranslationsThatAreNotFiniteOrAbsurdNameTheImageAndFile) {
  for (const bool binary : {false, true}) {
    for (const double bad : {kNaN, kInf, -kInf, 1e300}) {
      const std::string err = WorkspaceError(OneImageModel({0, bad, 100}), binary);
      EXPECT_TRUE(Has(err, binary ? "sparse/images.bin: " : "sparse/images.txt: ")) << err;
      EXPECT_TRUE(Has(err, "image \"nadir.jpg\" (image_id 7): implausible camera position")) << err;
    }
  }
  TempDir dir;
  WriteModel(OneImageModel({0, 0, 100}), false, dir);
  EXPECT_NO_THROW(ColmapWorkspace(dir.path().string(), ColmapDepthType::kGeometric));
}

TEST(ViewChecksTest, ColmapIntrinsicsThatAreAbsurdNameTheImageAndCamerasFile) {
  for (const bool binary : {false, true}) {
    const std::string err = WorkspaceError(OneImageModel({0, 0, 100}, 1e300), binary);
    EXPECT_TRUE(Has(err, binary ? "sparse/cameras.bin: " : "sparse/cameras.txt: ")) << err;
    EXPECT_TRUE(Has(err, "image \"nadir.jpg\" (image_id 7), camera_id 1: implausible focal length")) << err;
  }
}

TEST(ViewChecksTest, OpenMvsCentresThatAreAbsurdNameTheViewAndFile) {
  TempDir dir;
  DmapContents c;
  c.image_width = 64;
  c.image_height = 48;
  c.image_path = "a.png";
  c.view_ids = {0};
  c.camera.K = {50, 0, 31.5, 0, 50, 23.5, 0, 0, 1};
  c.camera.R = {1, 0, 0, 0, -1, 0, 0, 0, -1};
  c.camera.C = {0, 1e300, 100};
  c.depth = DepthMap(64, 48, 1, 100.0f);
  WriteDmap((dir / "depth0000.dmap").string(), c);
  const std::string err = InputErrorOf([&] { OpenMvsBlock block(dir.path().string()); });
  EXPECT_TRUE(Has(err, (dir / "depth0000.dmap").string() + ": view 0 (depth0000.dmap): implausible camera position"))
      << err;
}

TEST(ViewChecksTest, CameraFilePositionsThatAreAbsurdNameTheViewAndFile) {
  TempDir dir;
  const fs::path file = dir / "cameras.yaml";
  std::ofstream(file) << "views:\n  - {image: a.jpg, depth: a.tif, width_px: 64, height_px: 48, focal_px: 50,\n"
                         "     x_m: 1e300, y_m: 0, z_m: 100, omega_deg: 0, phi_deg: 0, kappa_deg: 0}\n";
  const std::string err = InputErrorOf([&] { RasterBlock block(file.string(), DepthKind::kZ, ""); });
  EXPECT_TRUE(Has(err, file.string() + ": line 2: view \"a.jpg\": implausible camera position")) << err;
}

TEST(ViewChecksTest, IntrinsicRules) {
  const auto err = [](const PinholeCamera& c) { return InputErrorOf([&] { CheckViewIntrinsics(c, "f", "view 1"); }); };
  EXPECT_NO_THROW(CheckViewIntrinsics(PinholeCamera::Centered(640, 480, 500), "f", "view 1"));
  EXPECT_TRUE(Has(err({640, 480, kNaN, 500, 320, 240}), "f: view 1: implausible focal length fx nan"));
  EXPECT_TRUE(Has(err({640, 480, 500, 1e9, 320, 240}), "implausible focal length"));
  EXPECT_TRUE(Has(err({640, 480, 1, 1, 320, 240}), "implausible focal length"));
  EXPECT_TRUE(Has(err({640, 480, 500, 500, kInf, 240}), "implausible principal point (inf, 240)"));
  EXPECT_TRUE(Has(err({640, 480, 500, 500, 320, 1e6}), "implausible principal point"));
  EXPECT_TRUE(Has(err({0, 480, 500, 500, 0, 240}), "implausible image size 0x480"));
  EXPECT_TRUE(Has(err({2000000, 480, 5e6, 5e6, 1e6, 240}), "implausible image size"));
}

TEST(ViewChecksTest, PoseRules) {
  Rigid3d pose;
  EXPECT_NO_THROW(CheckViewPose(pose, "f", "view 1"));
  pose.translation = {390000, 5.7e6, 1000};  // UTM-sized coordinates pass
  EXPECT_NO_THROW(CheckViewPose(pose, "f", "view 1"));
  pose.translation = {0, 0, 2e8};
  EXPECT_TRUE(Has(InputErrorOf([&] { CheckViewPose(pose, "f", "view 1"); }), "f: view 1: implausible camera position"));
  pose.translation = {0, 0, 0};
  pose.rotation.coeffs() << kNaN, 0, 0, 1;
  EXPECT_TRUE(Has(InputErrorOf([&] { CheckViewPose(pose, "f", "view 1"); }), "is not a finite unit quaternion"));
}

}  // namespace
}  // namespace sacfuse
