#include "io/camera_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/photogrammetric_orientation.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::TempDir;

fs::path WriteText(const TempDir& dir, const std::string& name, const std::string& text) {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

void ExpectError(const fs::path& path, const std::vector<std::string>& parts) {
  try {
    ReadCameraFile(path.string());
    ADD_FAILURE() << "no InputError for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    for (const std::string& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

// A worked YAML example: a 50 mm camera with 6 um pixels, the principal point 0.012 mm right of and 0.006 mm
// below the image centre.
const char* kYamlExample = R"(version: 1
cameras:
  nadir50: {width_px: 6132, height_px: 8176, focal_mm: 50.0, pixel_size_um: 6.0, ppx_mm: 0.012, ppy_mm: -0.006}
views:
  - image: 0001_nadir.jpg
    depth: depth/0001_nadir.tif
    image_path: images/0001_nadir.jpg
    camera: nadir50
    x_m: 390512.25
    y_m: 5705130.5
    z_m: 1065.0
    omega_deg: 0.5
    phi_deg: -1.25
    kappa_deg: 90.0
  - {image: 0002_nadir.jpg, depth: depth/0002_nadir.tif, camera: nadir50, focal_mm: 50.5,
     x_m: 390612.25, y_m: 5705130.5, z_m: 1066.0,
     rotation: [[0, -1, 0], [1, 0, 0], [0, 0, 1]], attitude_frame: local_enu}
)";

TEST(CameraFileTest, ReadsTheYamlExample) {
  TempDir dir;
  const auto views = ReadCameraFile(WriteText(dir, "cameras.yaml", kYamlExample).string()).views;
  ASSERT_EQ(views.size(), 2u);
  const CameraFileView& a = views[0];
  EXPECT_EQ(a.image, "0001_nadir.jpg");
  EXPECT_EQ(a.depth, "depth/0001_nadir.tif");
  EXPECT_EQ(a.image_path, "images/0001_nadir.jpg");
  EXPECT_EQ(a.camera.width, 6132);
  EXPECT_EQ(a.camera.height, 8176);
  EXPECT_NEAR(a.camera.fx, 50.0 / 0.006, 1e-9);
  EXPECT_NEAR(a.camera.fy, 50.0 / 0.006, 1e-9);
  EXPECT_NEAR(a.camera.cx, 3066.0 + 2.0, 1e-9);  // 0.012 mm right = 2 px right of the centre
  EXPECT_NEAR(a.camera.cy, 4088.0 + 1.0, 1e-9);  // 0.006 mm below (y up) = 1 px down
  EXPECT_FALSE(a.geodetic);
  EXPECT_EQ(a.position, Eigen::Vector3d(390512.25, 5705130.5, 1065.0));
  EXPECT_LT((a.rotation - ObjectFromPhotoCameraRotation({0.5, -1.25, 90.0})).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(a.attitude_frame, AttitudeFrame::kGrid);
  EXPECT_EQ(a.line, 5);
  const CameraFileView& b = views[1];
  EXPECT_EQ(b.image_path, "");
  EXPECT_NEAR(b.camera.fx, 50.5 / 0.006, 1e-9);  // the view's own field overrides its camera's
  EXPECT_EQ(b.rotation, ObjectFromPhotoCameraRotation({0, 0, 90}).array().round().matrix());
  EXPECT_EQ(b.attitude_frame, AttitudeFrame::kLocalEnu);
}

// A worked CSV example: pixel interior, geodetic positions (attitude then defaults to local ENU), a quoted
// image name with a comma, a comment and an empty image_path cell.
const char* kCsvExample =
    "# image,depth,... one view per line\n"
    "image,depth,image_path,width_px,height_px,focal_px,cx_px,cy_px,lat_deg,lon_deg,h_m,omega_deg,phi_deg,kappa_deg\n"
    "\"a,1.jpg\",depth/a1.tif,images/a1.jpg,320,240,1000,160.5,119.5,51.5,7.46,300,0,0,0\n"
    "b.jpg, depth/b.tif ,,320,240,1000,,,51.5001,7.4601,301.5,1,2,3\n";

TEST(CameraFileTest, ReadsTheCsvExample) {
  TempDir dir;
  const auto views = ReadCameraFile(WriteText(dir, "cams.csv", kCsvExample).string()).views;
  ASSERT_EQ(views.size(), 2u);
  EXPECT_EQ(views[0].image, "a,1.jpg");
  EXPECT_EQ(views[0].camera.cx, 160.5);
  EXPECT_EQ(views[0].camera.cy, 119.5);
  EXPECT_TRUE(views[0].geodetic);
  EXPECT_EQ(views[0].position, Eigen::Vector3d(51.5, 7.46, 300.0));
  EXPECT_EQ(views[0].attitude_frame, AttitudeFrame::kLocalEnu);
  EXPECT_EQ(views[0].rotation, Eigen::Matrix3d::Identity());
  EXPECT_EQ(views[0].line, 3);
  EXPECT_EQ(views[1].depth, "depth/b.tif");
  EXPECT_EQ(views[1].image_path, "");
  EXPECT_EQ(views[1].camera.cx, 160.0);  // absent: the image centre
  EXPECT_EQ(views[1].camera.cy, 120.0);
}

std::vector<CameraFileView> SampleViews() {
  std::vector<CameraFileView> views;
  for (int i = 0; i < 4; ++i) {
    CameraFileView v;
    v.image = i == 3 ? "sub dir/odd \"name\", #3.jpg" : "view_" + std::to_string(i) + ".jpg";
    v.depth = "depth/" + v.image + ".tif";
    v.image_path = i == 2 ? "" : "images/" + v.image + ".png";
    v.camera = {320 + i,       240,          1234.5678901234567 + i, i == 1 ? 1300.25 : 1234.5678901234567 + i,
                160.123456789, 119.987654321};
    v.geodetic = i % 2 == 1;
    v.position = v.geodetic ? Eigen::Vector3d(51.123456789012345 + i * 1e-4, 7.4567890123456789, 300.0 + i / 3.0)
                            : Eigen::Vector3d(390000.0 + i / 7.0, 5705000.0 + i / 3.0, 700.0 + i);
    v.rotation = ObjectFromPhotoCameraRotation({10.0 * i + 0.123, -20.0 + i / 7.0, 170.0 - i * 33.3});
    v.attitude_frame = i % 2 == 1 ? AttitudeFrame::kLocalEnu : AttitudeFrame::kGrid;
    views.push_back(v);
  }
  return views;
}

TEST(CameraFileTest, WriteReadRoundTripsEveryForm) {
  TempDir dir;
  const auto views = SampleViews();
  int n = 0;
  for (const char* ext : {".yaml", ".csv"}) {
    for (const bool matrix : {false, true}) {
      for (const double pitch_um : {0.0, 6.0}) {
        CameraFileWriteOptions o;
        o.rotation_matrix = matrix;
        o.pixel_size_um = pitch_um;
        const fs::path path = dir / ("c" + std::to_string(n++) + ext);
        WriteCameraFile(path.string(), CameraFile{views, {}}, o);
        const auto back = ReadCameraFile(path.string()).views;
        ASSERT_EQ(back.size(), views.size()) << path;
        for (size_t i = 0; i < views.size(); ++i) {
          SCOPED_TRACE(path.string() + " view " + std::to_string(i));
          EXPECT_EQ(back[i].image, views[i].image);
          EXPECT_EQ(back[i].depth, views[i].depth);
          EXPECT_EQ(back[i].image_path, views[i].image_path);
          EXPECT_EQ(back[i].camera.width, views[i].camera.width);
          EXPECT_EQ(back[i].camera.height, views[i].camera.height);
          for (const auto& [got, want] :
               {std::pair{back[i].camera.fx, views[i].camera.fx}, std::pair{back[i].camera.fy, views[i].camera.fy},
                std::pair{back[i].camera.cx, views[i].camera.cx}, std::pair{back[i].camera.cy, views[i].camera.cy}}) {
            EXPECT_NEAR(got, want, 1e-12 * std::abs(want));
          }
          EXPECT_EQ(back[i].geodetic, views[i].geodetic);
          EXPECT_EQ(back[i].position, views[i].position);  // 17 digits: the same doubles
          EXPECT_LE((back[i].rotation - views[i].rotation).cwiseAbs().maxCoeff(), matrix ? 0.0 : 1e-14);
          EXPECT_EQ(back[i].attitude_frame, views[i].attitude_frame);
        }
      }
    }
  }
  EXPECT_THROW(WriteCameraFile((dir / "c.txt").string(), CameraFile{views, {}}), Error);
  // Scene heights: YAML keeps them exactly, CSV cannot hold them.
  const CameraFile with_heights{views, {101.5, 99.25, 1.0 / 3.0}};
  WriteCameraFile((dir / "h.yaml").string(), with_heights);
  EXPECT_EQ(ReadCameraFile((dir / "h.yaml").string()).scene_heights_m, with_heights.scene_heights_m);
  EXPECT_TRUE(ReadCameraFile((dir / "c0.yaml").string()).scene_heights_m.empty());
  EXPECT_THROW(WriteCameraFile((dir / "h.csv").string(), with_heights), Error);
}

TEST(CameraFileTest, ErrorsNameFileLineViewAndField) {
  TempDir dir;
  const std::string head = "views:\n  - {image: a.jpg, depth: a.tif, width_px: 10, height_px: 8, focal_px: 20, ";
  const std::string pose = "x_m: 1, y_m: 2, z_m: 3, omega_deg: 0, phi_deg: 0, kappa_deg: 0";
  // Control: the base view reads.
  EXPECT_EQ(ReadCameraFile(WriteText(dir, "ok.yaml", head + pose + "}\n").string()).views.size(), 1u);

  ExpectError(WriteText(dir, "unknown.yaml", head + pose + ", focl_mm: 3}\n"),
              {"line 2", "view 1", "unknown field \"focl_mm\""});
  ExpectError(WriteText(dir, "nodepth.yaml",
                        "views:\n  - {image: a.jpg, width_px: 10, height_px: 8, focal_px: 20, " + pose + "}\n"),
              {"view 1 (\"a.jpg\")", "depth: missing"});
  ExpectError(WriteText(dir, "mixed.yaml", head + "focal_mm: 5, pixel_size_um: 2, " + pose + "}\n"),
              {"focal_mm", "mixes the millimetre interior"});
  ExpectError(WriteText(dir, "partial.yaml", head + "x_m: 1, y_m: 2, omega_deg: 0, phi_deg: 0, kappa_deg: 0}\n"),
              {"z_m", "missing", "a position in the project CRS needs all of them"});
  ExpectError(WriteText(dir, "both.yaml", head + pose + ", lat_deg: 1, lon_deg: 2, h_m: 3}\n"),
              {"either as x_m, y_m, z_m or as lat_deg, lon_deg, h_m"});
  ExpectError(WriteText(dir, "noatt.yaml", head + "x_m: 1, y_m: 2, z_m: 3}\n"), {"omega_deg", "missing"});
  ExpectError(
      WriteText(dir, "notrot.yaml", head + "x_m: 1, y_m: 2, z_m: 3, rotation: [[1, 0, 0], [0, 1, 0], [0, 0, -1]]}\n"),
      {"r11", "not a rotation matrix", "determinant -1"});
  ExpectError(WriteText(dir, "nan.yaml", head + "x_m: one, y_m: 2, z_m: 3, omega_deg: 0, phi_deg: 0, kappa_deg: 0}\n"),
              {"x_m", "\"one\" is not a finite number"});
  ExpectError(
      WriteText(dir, "width.yaml",
                "views:\n  - {image: a.jpg, depth: a.tif, width_px: 10.5, height_px: 8, focal_px: 20, " + pose + "}\n"),
      {"width_px", "positive integer"});
  ExpectError(
      WriteText(dir, "focal.yaml",
                "views:\n  - {image: a.jpg, depth: a.tif, width_px: 10, height_px: 8, focal_px: -2, " + pose + "}\n"),
      {"focal_px", "must be > 0"});
  ExpectError(WriteText(dir, "dup.yaml", head + pose + "}\n" + head.substr(7) + pose + "}\n"),
              {"line 3", "\"a.jpg\" is listed twice (first on line 2)"});
  // Repeated keys (yaml-cpp would keep one silently): in a view, in an interior, at the top level.
  ExpectError(WriteText(dir, "repeat.yaml", head + pose + ", x_m: 5}\n"),
              {"line 2", "view 1: x_m: duplicate key (first on line 2)"});
  ExpectError(WriteText(dir, "repeatcam.yaml", "cameras:\n  c1: {focal_px: 20,\n       focal_px: 30}\n"
                                               "views:\n  - {image: a.jpg, depth: a.tif, camera: c1, " + pose + "}\n"),
              {"line 3", "cameras.c1.focal_px: duplicate key (first on line 2)"});
  ExpectError(WriteText(dir, "repeattop.yaml", head + pose + "}\nversion: 1\nversion: 1\n"),
              {"line 4", "version: duplicate key (first on line 3)"});
  ExpectError(WriteText(dir, "frame.yaml", head + pose + ", attitude_frame: magnetic}\n"),
              {"attitude_frame", "neither grid nor local_enu"});
  ExpectError(WriteText(dir, "camid.yaml", "views:\n  - {image: a.jpg, depth: a.tif, camera: c9, " + pose + "}\n"),
              {"camera: \"c9\" is not under `cameras:`"});
  ExpectError(WriteText(dir, "top.yaml", "cams: {}\n" + std::string("views: []\n")),
              {"unknown top-level key \"cams\""});
  ExpectError(WriteText(dir, "empty.yaml", "views: []\n"), {"lists no views"});
  ExpectError(WriteText(dir, "heights.yaml", head + pose + "}\nscene_heights_m: [1, x2]\n"),
              {"line 3", "scene_heights_m", "\"x2\" is not a finite number"});
  ExpectError(WriteText(dir, "syntax.yaml", "views:\n  - {image: a.jpg\n  - ]\n"), {"not valid YAML"});
  ExpectError(WriteText(dir, "twodocs.yaml", head + pose + "}\n---\nversion: 2\n"),
              {"line 3", "a second YAML document starts here", "a camera file holds one document"});
  ExpectError(
      WriteText(dir, "lat.yaml", head + "lat_deg: 91, lon_deg: 2, h_m: 3, omega_deg: 0, phi_deg: 0, kappa_deg: 0}\n"),
      {"lat_deg", "outside [-90, 90]"});
  ExpectError(dir / "cameras.txt", {"neither .yaml/.yml nor .csv"});
  ExpectError(dir / "absent.yaml", {"does not exist"});

  const std::string csv_head = "image,depth,width_px,height_px,focal_px,x_m,y_m,z_m,omega_deg,phi_deg,kappa_deg\n";
  EXPECT_EQ(
      ReadCameraFile(WriteText(dir, "ok.csv", csv_head + "a.jpg,a.tif,10,8,20,1,2,3,0,0,0\n").string()).views.size(),
      1u);
  ExpectError(WriteText(dir, "cells.csv", csv_head + "a.jpg,a.tif,10,8,20,1,2,3,0,0\n"),
              {"line 2", "10 cells, but the header names 11 columns"});
  ExpectError(WriteText(dir, "column.csv", "image,depth,zoom\n"), {"line 1", "unknown column \"zoom\""});
  ExpectError(WriteText(dir, "quote.csv", csv_head + "\"a.jpg,a.tif,10,8,20,1,2,3,0,0,0\n"),
              {"unterminated quoted cell"});
  ExpectError(WriteText(dir, "noheader.csv", "# only a comment\n"), {"no header line"});
  ExpectError(WriteText(dir, "badnum.csv", csv_head + "a.jpg,a.tif,10,8,20,1,2,3e,0,0,0\n"),
              {"line 2", "view 1 (\"a.jpg\")", "z_m", "\"3e\" is not a finite number"});
}

}  // namespace
}  // namespace sacfuse
