#include "tools/bench/model_shift.h"

#include <filesystem>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"
#include "tools/bench/shifted_workspace.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// An oblique camera over a UTM-sized block and two sparse points on the ground.
ColmapModel UtmModel() {
  ColmapModel model;
  model.cameras[1] = ColmapCamera{1, "PINHOLE", 800, 600, {1000.0, 1001.0, 400.0, 300.0}};
  ColmapImage image;
  image.image_id = 3;
  image.camera_id = 1;
  image.name = "nadir/0000.jpg";
  // Looking down (camera z = world -z), tilted by 0.3 rad, turned by 1 rad about the vertical.
  image.cam_from_world_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) *
                                                     Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()) *
                                                     Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d centre(390123.4, 5705432.1, 650.0);
  image.cam_from_world_translation = -(image.cam_from_world_rotation * centre);
  model.images.push_back(image);
  ColmapPoint3D a, b;
  a.point3D_id = 1;
  a.xyz = {390100.0, 5705400.0, 110.0};
  b.point3D_id = 2;
  b.xyz = {391900.0, 5705800.0, 130.0};
  model.points3D[1] = a;
  model.points3D[2] = b;
  return model;
}

Eigen::Vector2d Project(const ColmapModel& model, const Eigen::Vector3d& world) {
  const ColmapImage& image = model.images.front();
  const ColmapCamera& cam = model.cameras.at(image.camera_id);
  const Eigen::Vector3d c = image.cam_from_world_rotation * world + image.cam_from_world_translation;
  return {cam.params[0] * c.x() / c.z() + cam.params[2], cam.params[1] * c.y() / c.z() + cam.params[3]};
}

TEST(ModelShiftTest, OffsetIsTheFlooredMeanOfTheSparsePoints) {
  const ColmapModel model = UtmModel();  // mean (391000, 5705600, 120)
  EXPECT_EQ(ChooseModelOffset(model), Eigen::Vector3d(391000.0, 5705000.0, 0.0));
  EXPECT_EQ(ChooseModelOffset(model, 100.0), Eigen::Vector3d(391000.0, 5705600.0, 100.0));
  ColmapModel no_points = model;
  no_points.points3D.clear();  // camera centre (390123.4, 5705432.1, 650)
  EXPECT_EQ(ChooseModelOffset(no_points), Eigen::Vector3d(390000.0, 5705000.0, 0.0));
  EXPECT_THROW(ChooseModelOffset(ColmapModel()), Error);
}

TEST(ModelShiftTest, ShiftedPointProjectsToTheSamePixel) {
  const ColmapModel model = UtmModel();
  ColmapModel shifted = model;
  const Eigen::Vector3d offset = ChooseModelOffset(model);
  ShiftColmapModel(&shifted, offset);
  const Eigen::Vector3d ground(390111.1, 5705444.4, 123.4);
  const Eigen::Vector2d before = Project(model, ground);
  const Eigen::Vector2d after = Project(shifted, ground - offset);
  EXPECT_NEAR((before - after).norm(), 0.0, 1e-6) << before.transpose() << " vs " << after.transpose();
  const ColmapImage& img = model.images[0];
  EXPECT_GT((img.cam_from_world_rotation * ground + img.cam_from_world_translation).z(), 100.0);  // in front
  // Camera centre and sparse points move by -offset; rotation and intrinsics stay.
  EXPECT_NEAR((ColmapCameraCentre(shifted.images[0]) - (ColmapCameraCentre(model.images[0]) - offset)).norm(), 0.0,
              1e-6);
  EXPECT_EQ(shifted.points3D.at(2).xyz, model.points3D.at(2).xyz - offset);
  EXPECT_TRUE(shifted.images[0].cam_from_world_rotation.isApprox(model.images[0].cam_from_world_rotation, 0.0));
  EXPECT_EQ(shifted.cameras.at(1).params, model.cameras.at(1).params);
  // In the local frame float32 keeps sub-millimetre precision, in UTM it does not.
  const Eigen::Vector3d local = ground - offset;
  EXPECT_LT((local.cast<float>().cast<double>() - local).norm(), 1e-4);
  EXPECT_GT((ground.cast<float>().cast<double>() - ground).norm(), 0.01);
}

TEST(ShiftedWorkspaceTest, WritesTheShiftedModelAndLinksTheMaps) {
  TempDir dir;
  const fs::path src = dir / "block";
  for (const char* d : {"sparse", "images/nadir", "stereo/depth_maps", "stereo/normal_maps"}) {
    fs::create_directories(src / d);
  }
  std::ofstream(src / "stereo" / "fusion.cfg") << "nadir/0000.jpg\n";
  const ColmapModel model = UtmModel();
  WriteColmapModelText(model, (src / "sparse").string());

  const fs::path dest = dir / "out" / "workspace";
  for (int round = 0; round < 2; ++round) {  // a second run refreshes the links and the model
    const ShiftedWorkspace ws = PrepareShiftedWorkspace(src.string(), dest.string());
    EXPECT_EQ(ws.offset, Eigen::Vector3d(391000.0, 5705000.0, 0.0));
    EXPECT_EQ(ws.images, 1u);
    EXPECT_EQ(ws.points3D, 2u);
    EXPECT_TRUE(fs::is_symlink(dest / "images"));
    EXPECT_TRUE(fs::is_symlink(dest / "stereo"));
    EXPECT_TRUE(fs::exists(dest / "stereo" / "fusion.cfg"));
    EXPECT_TRUE(fs::exists(dest / "sparse" / "images.bin"));
    const ColmapModel back = ReadColmapModel((dest / "sparse").string());
    const Eigen::Vector3d ground(390111.1, 5705444.4, 123.4);
    EXPECT_NEAR((Project(back, ground - ws.offset) - Project(model, ground)).norm(), 0.0, 1e-6);
    EXPECT_EQ(back.points3D.at(1).xyz, model.points3D.at(1).xyz - ws.offset);
  }
  // The source is never touched: still the text model only.
  EXPECT_FALSE(fs::exists(src / "sparse" / "images.bin"));
}

TEST(ShiftedWorkspaceTest, NamesWhatStereoFusionWouldMiss) {
  TempDir dir;
  const fs::path src = dir / "block";
  for (const char* d : {"sparse", "images", "stereo/depth_maps"}) fs::create_directories(src / d);
  try {
    PrepareShiftedWorkspace(src.string(), (dir / "out").string());
    FAIL() << "no error without normal maps";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("normal_maps"), std::string::npos) << e.what();
  }
  fs::create_directories(src / "stereo" / "normal_maps");
  EXPECT_THROW(PrepareShiftedWorkspace(src.string(), (dir / "out").string()), InputError);  // no fusion.cfg
}

}  // namespace
}  // namespace sacfuse
