#include "io/raster_block.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/backproject.h"
#include "io/crs.h"
#include "core/error.h"
#include "core/photogrammetric_orientation.h"
#include "io/raster_block_writer.h"
#include "io/rgb_image_file.h"
#include "io/tiff_depth.h"
#include "tests/support/gtx_grid.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::TempDir;

constexpr double kGroundZ = 40.0;  // the scene: the horizontal plane z = 40 m

// A camera looking at the ground plane: centre, omega/phi/kappa w.r.t. the grid, 64x48 px image.
struct TestCamera {
  std::string name;
  Eigen::Vector3d centre;
  OmegaPhiKappa angles;
};

std::vector<TestCamera> TestCameras(const Eigen::Vector3d& origin) {
  return {{"nadir.jpg", origin + Eigen::Vector3d(0, 0, 140), {0, 0, 0}},
          {"sub/oblique.jpg", origin + Eigen::Vector3d(30, -50, 120), {35, 5, 20}},
          {"rolled.jpg", origin + Eigen::Vector3d(-20, 10, 160), {-3, 12, -100}}};
}

PinholeCamera TestIntrinsics() { return {64, 48, 70.0, 72.0, 33.25, 23.5}; }

// Depth of the plane z = kGroundZ at every pixel centre of `depth_camera`: z along the axis or range.
DepthMap PlaneDepth(const PinholeCamera& depth_camera, const Rigid3d& cam_from_world, bool range) {
  const Rigid3d world_from_cam = cam_from_world.Inverse();
  DepthMap d(depth_camera.width, depth_camera.height);
  for (int r = 0; r < d.height; ++r) {
    for (int c = 0; c < d.width; ++c) {
      const Eigen::Vector3d ray_cam((c + 0.5 - depth_camera.cx) / depth_camera.fx,
                                    (r + 0.5 - depth_camera.cy) / depth_camera.fy, 1.0);
      const Eigen::Vector3d ray_world = world_from_cam.rotation * ray_cam;
      const double t = (kGroundZ - world_from_cam.translation.z()) / ray_world.z();  // = z in the camera
      d.at(r, c) = t > 0 ? static_cast<float>(range ? t * ray_cam.norm() : t) : 0.0f;
    }
  }
  d.at(3, 4) = std::nanf("");  // one invalid pixel
  return d;
}

// Writes a block of TestCameras: the camera file `file_name` plus depth rasters at `depth_scale` of the image
// size; positions geodetic (with `crs`) or in the grid; returns the camera file path.
std::string WriteBlock(const TempDir& dir, const std::string& file_name, double depth_scale, bool range, bool geodetic,
                       const Crs& crs, const Eigen::Vector3d& origin) {
  std::vector<CameraFileView> views;
  for (const TestCamera& tc : TestCameras(origin)) {
    CameraFileView v;
    v.image = tc.name;
    v.depth = "depth/" + tc.name + ".tif";
    v.camera = TestIntrinsics();
    const Eigen::Matrix3d rotation = ObjectFromPhotoCameraRotation(tc.angles);
    const Rigid3d pose = CamFromWorldFromPhotogrammetric(rotation, tc.centre);
    const PinholeCamera dc = v.camera.Scaled(static_cast<int>(std::lround(64 * depth_scale)),
                                             static_cast<int>(std::lround(48 * depth_scale)));
    WriteTiffDepth((dir / v.depth).string(), PlaneDepth(dc, pose, range));
    v.rotation = rotation;
    v.position = tc.centre;
    if (geodetic) {
      v.geodetic = true;
      v.position = GeodeticFromProject(crs, tc.centre);
      v.attitude_frame = AttitudeFrame::kLocalEnu;
      v.rotation = ProjectFromLocalEnuRotation(crs, v.position.x(), v.position.y()).transpose() * rotation;
    }
    views.push_back(v);
  }
  const std::string path = (dir / file_name).string();
  WriteCameraFile(path, CameraFile{views, {}});
  return path;
}

// Every valid depth pixel back-projects onto the plane, and exactly one pixel is invalid.
void ExpectPointsOnThePlane(const RasterBlock& block, double tol_m) {
  for (const View& view : block.views()) {
    const DepthMap depth = block.ReadDepthMap(view);
    const PinholeCamera dc = view.camera.Scaled(depth.width, depth.height);
    const Rigid3d world_from_cam = view.cam_from_world.Inverse();
    size_t valid = 0;
    double worst = 0;
    for (int r = 0; r < depth.height; ++r) {
      for (int c = 0; c < depth.width; ++c) {
        if (!IsValidDepth(depth.at(r, c))) continue;
        ++valid;
        worst = std::max(worst, std::abs(DepthPixelToWorld(dc, world_from_cam, c, r, depth.at(r, c)).z() - kGroundZ));
      }
    }
    EXPECT_EQ(valid, depth.num_pixels() - 1) << view.name;
    EXPECT_LT(worst, tol_m) << view.name;
  }
}

TEST(RasterBlockTest, ZAndRangeDepthsAtFullAndHalfSizeBackProjectOntoTheScene) {
  const Eigen::Vector3d origin(1000, 2000, 0);
  for (const double scale : {1.0, 0.5}) {
    for (const bool range : {false, true}) {
      TempDir dir;
      const std::string file = WriteBlock(dir, "cameras.yaml", scale, range, false, {}, origin);
      const RasterBlock block(file, range ? DepthKind::kRange : DepthKind::kZ, "");
      ASSERT_EQ(block.views().size(), 3u);
      EXPECT_EQ(block.views()[1].name, "sub/oblique.jpg");
      EXPECT_EQ(block.views()[1].index, 1u);
      EXPECT_EQ(block.DepthSize(block.views()[0]).width, static_cast<int>(64 * scale));
      ExpectPointsOnThePlane(block, 1e-4);
      // The nadir's principal-point ray hits the ground right below the centre.
      const View& nadir = block.views()[0];
      EXPECT_LT((nadir.CenterInWorld() - (origin + Eigen::Vector3d(0, 0, 140))).norm(), 1e-9);
      EXPECT_LT((nadir.ViewDirectionInWorld() - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
      // Windows equal the whole raster's pixels (range converted with the right pixel positions).
      const DepthMap whole = block.ReadDepthMap(block.views()[1]);
      const PixelWindow w{2, whole.height - 3, 5, whole.width - 1};
      const DepthMap win = block.ReadDepthWindow(block.views()[1], w);
      for (int r = 0; r < w.height(); ++r) {
        for (int c = 0; c < w.width(); ++c) ASSERT_EQ(win.at(r, c), whole.at(w.row_begin + r, w.col_begin + c));
      }
      // Sampled scene heights are the plane's.
      const std::vector<double> z = block.SceneHeights();
      ASSERT_GT(z.size(), 100u);
      for (const double h : z) ASSERT_NEAR(h, kGroundZ, 1e-4);
    }
  }
}

TEST(RasterBlockTest, GeodeticPositionsWithLocalEnuAttitudes) {
  const Crs crs = ParseProjectCrs("EPSG:25832");
  const Eigen::Vector3d origin(470000.0, 5650000.0, 0.0);  // west of the zone's central meridian (9 E)
  TempDir dir;
  const std::string file = WriteBlock(dir, "cameras.csv", 1.0, false, true, crs, origin);
  const RasterBlock block(file, DepthKind::kZ, "EPSG:25832");
  ExpectPointsOnThePlane(block, 1e-4);
  EXPECT_LT((block.views()[0].CenterInWorld() - (origin + Eigen::Vector3d(0, 0, 140))).norm(), 1e-6);
  // Without the crs key: a ConfigError naming it.
  try {
    RasterBlock(file, DepthKind::kZ, "");
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("crs"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("geodetic position"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nadir.jpg"), std::string::npos) << e.what();
  }
}

// Known answer: a camera at 51 N 10 E (1 degree east of zone 32's central meridian) with omega = phi = kappa = 0
// w.r.t. local ENU looks straight down with its image top toward TRUE north, which on the UTM grid points
// gamma ~ (lon - 9 deg) * sin(lat) = 0.777 deg west of grid north (the meridian convergence).
TEST(RasterBlockTest, LocalEnuAttitudeIsTurnedByTheMeridianConvergence) {
  TempDir dir;
  std::ofstream(dir / "c.yaml") << "views:\n  - {image: a.jpg, depth: a.tif, width_px: 10, height_px: 8, focal_px: 20,"
                                   " lat_deg: 51, lon_deg: 10, h_m: 500, omega_deg: 0, phi_deg: 0, kappa_deg: 0}\n";
  const RasterBlock block((dir / "c.yaml").string(), DepthKind::kZ, "EPSG:25832");
  const Rigid3d& pose = block.views()[0].cam_from_world;
  const Eigen::Vector3d down = pose.rotation.conjugate() * Eigen::Vector3d(0, 0, 1);
  const Eigen::Vector3d top = pose.rotation.conjugate() * Eigen::Vector3d(0, -1, 0);
  EXPECT_LT((down - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  const double gamma_deg = std::atan2(-top.x(), top.y()) * 180.0 / M_PI;  // counter-clockwise from grid north
  EXPECT_NEAR(gamma_deg, 1.0 * std::sin(51.0 * M_PI / 180.0), 0.01);
  EXPECT_GT(gamma_deg, 0.7);
  // The same attitude w.r.t. the grid has its top exactly on grid north.
  std::ofstream(dir / "g.yaml") << "attitude_frame: grid\nviews:\n  - {image: a.jpg, depth: a.tif, width_px: 10, "
                                   "height_px: 8, focal_px: 20, lat_deg: 51, lon_deg: 10, h_m: 500, omega_deg: 0, "
                                   "phi_deg: 0, kappa_deg: 0}\n";
  const RasterBlock grid((dir / "g.yaml").string(), DepthKind::kZ, "EPSG:25832");
  const Eigen::Vector3d grid_top = grid.views()[0].cam_from_world.rotation.conjugate() * Eigen::Vector3d(0, -1, 0);
  EXPECT_LT((grid_top - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_LT((grid.views()[0].CenterInWorld() - block.views()[0].CenterInWorld()).norm(), 1e-8);
}

// A workspace in a local frame: input.origin_m moves every position (x_m, y_m, z_m) and the scene heights by it.
TEST(RasterBlockTest, OriginMovesPositionsAndSceneHeights) {
  TempDir dir;
  const std::string file = WriteBlock(dir, "cameras.yaml", 1.0, false, false, {}, Eigen::Vector3d::Zero());
  CameraFile with_heights = ReadCameraFile(file);
  with_heights.scene_heights_m = {kGroundZ, kGroundZ + 12.5};
  WriteCameraFile(file, with_heights);
  const Eigen::Vector3d origin(770000.0, 6277000.0, 0.0);
  const RasterBlock local(file, DepthKind::kZ, "");
  const RasterBlock moved(file, DepthKind::kZ, CameraFrame("EPSG:2154", "", origin));
  ExpectPointsOnThePlane(moved, 1e-4);
  for (size_t i = 0; i < local.views().size(); ++i) {
    const Eigen::Vector3d shift = moved.views()[i].CenterInWorld() - local.views()[i].CenterInWorld();
    EXPECT_LT((shift - origin).norm(), 1e-8) << i;  // 7e5..6e6 m: a few units of the last bit
    EXPECT_TRUE(moved.views()[i].cam_from_world.rotation.isApprox(local.views()[i].cam_from_world.rotation, 1e-15));
  }
  EXPECT_EQ(moved.SceneHeights(), (std::vector<double>{kGroundZ, kGroundZ + 12.5}));
  const RasterBlock raised(file, DepthKind::kZ, CameraFrame("", "", Eigen::Vector3d(0, 0, 7.25)));
  EXPECT_EQ(raised.SceneHeights(), (std::vector<double>{kGroundZ + 7.25, kGroundZ + 12.5 + 7.25}));
  // Geodetic positions are absolute: an origin with them is an error naming both.
  TempDir geo_dir;
  const Crs utm = ParseProjectCrs("EPSG:25832");
  const std::string geo = WriteBlock(geo_dir, "g.yaml", 1.0, false, true, utm, {470000.0, 5650000.0, 0.0});
  try {
    RasterBlock(geo, DepthKind::kZ, CameraFrame("EPSG:25832", "", origin));
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("input.origin_m applies to x_m, y_m, z_m"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nadir.jpg"), std::string::npos) << e.what();
  }
}

// A camera file in WGS 84 / UTM 31N for a Lambert-93 project: positions go through PROJ, grid attitudes turn by
// the difference of the two grids' convergences, so the block still lands on its plane and every camera looks
// along the same ground directions.
TEST(RasterBlockTest, CamerasInAnotherProjectedCrsAreTransformed) {
  TempDir dir;
  const Eigen::Vector3d utm_origin(570000.0, 4828000.0, 0.0);  // near Montpellier, 43.6 N 3.87 E
  const std::string file = WriteBlock(dir, "cameras.yaml", 1.0, false, false, {}, utm_origin);
  const RasterBlock utm(file, DepthKind::kZ, "EPSG:32631");
  const RasterBlock lambert(file, DepthKind::kZ, CameraFrame("EPSG:2154", "EPSG:32631"));
  ExpectPointsOnThePlane(lambert, 2e-3);
  const Crs utm_crs = ParseProjectCrs("EPSG:32631"), lambert_crs = ParseProjectCrs("EPSG:2154");
  for (size_t i = 0; i < utm.views().size(); ++i) {
    // Centres: through latitude/longitude (WGS 84 and RGF93 v1: EPSG's null transformation).
    const Eigen::Vector3d g = GeodeticFromProject(utm_crs, utm.views()[i].CenterInWorld());
    EXPECT_LT((lambert.views()[i].CenterInWorld() - ProjectFromGeodetic(lambert_crs, g.x(), g.y(), g.z())).norm(),
              1e-6);
    // Viewing directions: the same tilt (a rotation about the vertical), and the azimuth a step along the UTM
    // direction has once carried over point by point (the grids' scales differ by 7e-4, which the rotation leaves
    // out: depths are metres).
    const Eigen::Vector3d d_utm = utm.views()[i].ViewDirectionInWorld();
    const Eigen::Vector3d d_lambert = lambert.views()[i].ViewDirectionInWorld();
    EXPECT_NEAR(d_lambert.z(), d_utm.z(), 1e-12) << i;
    if (d_utm.head<2>().norm() < 0.1) continue;  // the nadir has no azimuth to speak of
    const Eigen::Vector3d c_utm = utm.views()[i].CenterInWorld();
    const Eigen::Vector3d g2 = GeodeticFromProject(utm_crs, c_utm + 10.0 * d_utm);
    const Eigen::Vector3d along = ProjectFromGeodetic(lambert_crs, g2.x(), g2.y(), g2.z()) -
                                  ProjectFromGeodetic(lambert_crs, g.x(), g.y(), g.z());
    EXPECT_NEAR(std::atan2(d_lambert.x(), d_lambert.y()), std::atan2(along.x(), along.y()), 1e-6) << i;
    // ... which is not the UTM azimuth: the grids' convergences here, 0.600 (UTM 31N) and 0.631 degrees
    // (Lambert-93), differ by 5.4e-4 rad.
    EXPECT_NEAR(std::atan2(d_lambert.x(), d_lambert.y()) - std::atan2(d_utm.x(), d_utm.y()), -5.4e-4, 0.2e-4) << i;
  }
  // Not without crs.
  EXPECT_THROW(RasterBlock(file, DepthKind::kZ, CameraFrame("", "EPSG:32631")), ConfigError);
}

// Latitude/longitude with ellipsoidal heights into Lambert-93 + NGF-IGN69: the height goes through the geoid grid
// (a hand-made stand-in for RAF18, geoid 50 m); without the grid the camera cannot be placed, naming the grid.
TEST(RasterBlockTest, GeodeticPositionsGetOrthometricHeightsThroughTheGeoidGrid) {
  TempDir dir, grids;
  std::ofstream(dir / "c.yaml") << "views:\n  - {image: a.jpg, depth: a.tif, width_px: 10, height_px: 8, focal_px: 20,"
                                   " lat_deg: 43.6, lon_deg: 3.87, h_m: 250, omega_deg: 0, phi_deg: 0, kappa_deg: 0}\n";
  SetExtraProjSearchPaths({});
  try {
    RasterBlock((dir / "c.yaml").string(), DepthKind::kZ, "EPSG:2154+5720");
    ADD_FAILURE() << "placed without a geoid grid (or PROJ has RAF18 installed)";
  } catch (const InputError& e) {
    const std::string m = e.what();
    for (const char* part : {"a.jpg", "crs \"EPSG:2154+5720\"", "fr_ign_RAF18.tif", "search path"}) {
      EXPECT_NE(m.find(part), std::string::npos) << part << " in " << m;
    }
  }
  testing::WriteGtxGrid(grids / "RAF18.gtx", 42.0, 1.0, 0.5, 9, 11, 50.0);
  SetExtraProjSearchPaths({grids.path().string()});
  const RasterBlock block((dir / "c.yaml").string(), DepthKind::kZ, "EPSG:2154+5720");
  SetExtraProjSearchPaths({});
  const Eigen::Vector3d centre = block.views()[0].CenterInWorld();
  EXPECT_NEAR(centre.z(), 200.0, 1e-3);  // H = h - N
  EXPECT_LT((centre.head<2>() - ProjectFromGeodetic(ParseProjectCrs("EPSG:2154"), 43.6, 3.87, 0.0).head<2>()).norm(),
            1e-6);
}

TEST(RasterBlockTest, BadRastersAndImagesNameFileAndView) {
  TempDir dir;
  const std::string file = WriteBlock(dir, "cameras.yaml", 1.0, false, false, {}, {0, 0, 0});
  const RasterBlock block(file, DepthKind::kZ, "");
  const View& view = block.views()[2];
  const auto expect_error = [&](const auto& fn, const std::string& file_part, const std::string& what) {
    try {
      fn();
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_NE(e.file().find(file_part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("rolled.jpg"), std::string::npos) << e.what();
    }
  };
  // Wrong aspect (a 30x30 raster for a 64x48 image).
  WriteTiffDepth(block.DepthMapPath(view), DepthMap(30, 30, 1, 5.0f));
  expect_error([&] { block.DepthSize(view); }, "rolled.jpg.tif", "is not the image size 64x48");
  expect_error([&] { block.ReadDepthWindow(view, {0, 2, 0, 2}); }, "rolled.jpg.tif", "is not the image size");
  // Missing raster.
  fs::remove(block.DepthMapPath(view));
  expect_error([&] { block.ReadDepthMap(view); }, "rolled.jpg.tif", "does not exist");
  // No image path: no colours; an image of the wrong size: an error.
  EXPECT_TRUE(block.ReadImage(view).empty());
  std::ofstream(dir / "with_image.yaml")
      << "views:\n  - {image: rolled.jpg, depth: d.tif, image_path: img/rolled.png, width_px: 64, height_px: 48, "
         "focal_px: 20, x_m: 0, y_m: 0, z_m: 100, omega_deg: 0, phi_deg: 0, kappa_deg: 0}\n";
  const RasterBlock with_image((dir / "with_image.yaml").string(), DepthKind::kZ, "");
  WriteRgbImagePng((dir / "img/rolled.png").string(), RgbImage(64, 48, 3, 7));
  EXPECT_EQ(with_image.ReadImage(with_image.views()[0]).at(47, 63, 2), 7);
  WriteRgbImagePng((dir / "img/rolled.png").string(), RgbImage(32, 24, 3, 7));
  expect_error([&] { with_image.ReadImage(with_image.views()[0]); }, "rolled.png",
               "image is 32x24 but its camera is 64x48");
}

TEST(RasterBlockTest, FindCameraFileAndDepthKind) {
  TempDir dir;
  EXPECT_THROW(FindCameraFile(dir.path().string()), InputError);
  std::ofstream(dir / "cameras.csv") << "x\n";
  EXPECT_EQ(FindCameraFile(dir.path().string()), (dir / "cameras.csv").string());
  std::ofstream(dir / "cameras.yaml") << "x\n";
  EXPECT_THROW(FindCameraFile(dir.path().string()), InputError);
  EXPECT_EQ(ParseDepthKind("range"), DepthKind::kRange);
  EXPECT_THROW(ParseDepthKind("disparity"), ConfigError);
}

// WriteRasterBlock of a RasterBlock reads back to the same poses and depths, in every camera-file form.
TEST(RasterBlockTest, WriterRoundTripsEveryForm) {
  TempDir src;
  const Crs crs = ParseProjectCrs("EPSG:25832");
  const Eigen::Vector3d origin(390000.0, 5705000.0, 0.0);
  const RasterBlock input(WriteBlock(src, "cameras.yaml", 0.5, false, false, {}, origin), DepthKind::kZ, "EPSG:25832");
  struct Form {
    std::string file;
    bool matrix, geodetic, enu, range;
    double pitch_um;
  };
  for (const Form& f :
       {Form{"cameras.yaml", false, false, false, false, 0.0}, Form{"c.csv", true, false, false, true, 1.0},
        Form{"g.yaml", false, true, true, false, 0.0}, Form{"e.csv", true, false, true, true, 6.0}}) {
    SCOPED_TRACE(f.file);
    TempDir out;
    RasterBlockWriteOptions o;
    o.camera_file_name = f.file;
    o.camera.rotation_matrix = f.matrix;
    o.camera.pixel_size_um = f.pitch_um;
    o.geodetic_positions = f.geodetic;
    o.attitude_frame = f.enu ? AttitudeFrame::kLocalEnu : AttitudeFrame::kGrid;
    o.crs = crs;
    o.depth_kind = f.range ? DepthKind::kRange : DepthKind::kZ;
    o.tiff.nodata = std::nanf("");
    const std::string camera_file = WriteRasterBlock(input, out.path().string(), o);
    EXPECT_FALSE(fs::exists(out / "images"));  // the input has no images
    const RasterBlock back(camera_file, o.depth_kind, "EPSG:25832");
    ASSERT_EQ(back.views().size(), input.views().size());
    // YAML carries the input's scene heights (same tile planning); CSV falls back to sampling its own depths.
    if (fs::path(f.file).extension() == ".yaml") {
      EXPECT_EQ(back.SceneHeights(), input.SceneHeights());
    } else {
      EXPECT_EQ(back.SceneHeights().size(), input.SceneHeights().size());
    }
    for (size_t i = 0; i < input.views().size(); ++i) {
      const View& a = input.views()[i];
      const View& b = back.views()[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_NEAR(a.camera.fx, b.camera.fx, 1e-9);
      EXPECT_NEAR(a.camera.cy, b.camera.cy, 1e-9);
      for (const Eigen::Vector3d& x :
           {Eigen::Vector3d(origin), Eigen::Vector3d(origin + Eigen::Vector3d(80, 60, 40))}) {
        EXPECT_LT((a.cam_from_world * x - b.cam_from_world * x).norm(), 1e-6);
      }
      const DepthMap da = input.ReadDepthMap(a), db = back.ReadDepthMap(b);
      ASSERT_EQ(da.width, db.width);
      for (size_t k = 0; k < da.data.size(); ++k) {
        if (!f.range) {
          ASSERT_EQ(da.data[k], db.data[k]);
        } else {
          ASSERT_NEAR(da.data[k], db.data[k], 2e-5 * da.data[k]);  // float rounding of range and back
        }
      }
    }
  }
  RasterBlockWriteOptions geo;
  geo.geodetic_positions = true;
  TempDir out;
  EXPECT_THROW(WriteRasterBlock(input, out.path().string(), geo), ConfigError);  // no crs
}

}  // namespace
}  // namespace sacfuse
