// OpenMvsBlock: camera conventions against OpenMVS's own formulas, the folder listing, images, windows, scene
// heights, the writer's round trip and bad input.
#include "io/openmvs_block.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "tests/support/error_of.h"

#include "core/backproject.h"
#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// A binary PPM (which OpenCV decodes everywhere): pixel (row, col) = (10 row + col, 100 + col, 200 - row).
void WritePpm(const fs::path& path, int width, int height) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << width << " " << height << "\n255\n";
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      out.put(static_cast<char>(10 * r + c)).put(static_cast<char>(100 + c)).put(static_cast<char>(200 - r));
    }
  }
}

// Nadir camera (x east, y south, z down) at (x, y, 105) over a flat ground at z = 5: every depth is 100 m.
DmapContents NadirDmap(double x, double y, int image_w, int image_h, int depth_w, int depth_h,
                       const std::string& image_path) {
  DmapContents c;
  c.image_width = static_cast<uint32_t>(image_w);
  c.image_height = static_cast<uint32_t>(image_h);
  c.image_path = image_path;
  c.view_ids = {0, 1};
  c.camera.K = {50.0, 0.0, image_w / 2.0 - 0.5, 0.0, 50.0, image_h / 2.0 - 0.5, 0.0, 0.0, 1.0};
  c.camera.R = {1, 0, 0, 0, -1, 0, 0, 0, -1};
  c.camera.C = {x, y, 105.0};
  c.depth = DepthMap(depth_w, depth_h, 1, 100.0f);
  c.depth_min = c.depth_max = 100.0f;
  return c;
}

// OpenMVS's back-projection of depth pixel (col, row) (Scene::LoadDMAP): K scaled to the depth map per axis by
// Camera::ScaleK (f s, (c + 0.5) s - 0.5), then X = R^T K^-1 (col d, row d, d) + C.
Eigen::Vector3d OpenMvsBackProject(const DmapContents& c, int col, int row) {
  const double sx = static_cast<double>(c.depth.width) / c.image_width;
  const double sy = static_cast<double>(c.depth.height) / c.image_height;
  const double fx = c.camera.K[0] * sx, fy = c.camera.K[4] * sy;
  const double cx = (c.camera.K[2] + 0.5) * sx - 0.5, cy = (c.camera.K[5] + 0.5) * sy - 0.5;
  const double d = c.depth.at(row, col);
  const Eigen::Vector3d x_cam((col - cx) / fx * d, (row - cy) / fy * d, d);
  Eigen::Matrix3d R;
  for (int i = 0; i < 9; ++i) R(i / 3, i % 3) = c.camera.R[i];
  return R.transpose() * x_cam + Eigen::Vector3d(c.camera.C[0], c.camera.C[1], c.camera.C[2]);
}

struct CollectingSink : PointSink {
  std::vector<FusedPoint> points;
  void Write(const FusedPoint* p, size_t n) override { points.insert(points.end(), p, p + n); }
};

using testing::InputErrorOf;

TEST(OpenMvsBlockTest, CameraConventionsKnownAnswer) {
  DmapHeader h;
  h.image_width = 640;
  h.image_height = 480;
  h.camera.K = {1000.0, 0.0, 319.5, 0.0, 1001.0, 239.5, 0.0, 0.0, 1.0};
  h.camera.R = {1, 0, 0, 0, -1, 0, 0, 0, -1};
  h.camera.C = {10.0, 20.0, 100.0};
  const PinholeCamera cam = PinholeFromDmap(h, "f.dmap", "");
  EXPECT_EQ(cam.width, 640);
  EXPECT_EQ(cam.height, 480);
  EXPECT_EQ(cam.fx, 1000.0);
  EXPECT_EQ(cam.fy, 1001.0);
  EXPECT_EQ(cam.cx, 320.0);  // pixel centre 319.5 -> corner convention
  EXPECT_EQ(cam.cy, 240.0);
  const Rigid3d pose = CamFromWorldFromDmap(h.camera, "f.dmap", "");
  EXPECT_NEAR((pose.translation - Eigen::Vector3d(-10.0, 20.0, 100.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((pose * Eigen::Vector3d(10.0, 20.0, 0.0) - Eigen::Vector3d(0, 0, 100)).norm(), 0.0, 1e-12);

  View view;
  view.camera = cam;
  view.cam_from_world = pose;
  const DmapCamera back = DmapCameraFromView(view);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(back.K[i], h.camera.K[i], 1e-12) << i;
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(back.R[i], h.camera.R[i], 1e-15) << i;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back.C[i], h.camera.C[i], 1e-12) << i;
}

// The same world points as OpenMVS for a tilted camera at UTM-sized coordinates, with the depth map at the image
// size, at half size, and at an uneven per-axis scale.
TEST(OpenMvsBlockTest, BackProjectionMatchesOpenMvs) {
  TempDir dir;
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, -0.4).normalized()) *
       Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  int number = 0;
  for (const auto& [dw, dh] : std::vector<std::pair<int, int>>{{64, 48}, {32, 24}, {21, 17}}) {
    DmapContents c = NadirDmap(0, 0, 64, 48, dw, dh, "a.ppm");
    c.camera.K = {70.0, 0.0, 30.25, 0.0, 72.5, 25.75, 0.0, 0.0, 1.0};
    for (int i = 0; i < 9; ++i) c.camera.R[i] = R(i / 3, i % 3);
    c.camera.C = {512345.678, 5412345.125, 987.5};
    for (int r = 0; r < dh; ++r) {
      for (int col = 0; col < dw; ++col) c.depth.at(r, col) = 400.0f + 3.0f * r - 2.0f * col;
    }
    const std::string name = "depth000" + std::to_string(number++) + ".dmap";
    WriteDmap((dir / name).string(), c);
    WritePpm(dir / "a.ppm", 64, 48);
    const OpenMvsBlock block(dir.path().string());
    const View& view = block.views().back();
    ASSERT_EQ(view.name, name);
    CollectingSink sink;
    ASSERT_EQ(BackprojectDepthMap(view, block.ReadDepthMap(view), nullptr, sink), static_cast<size_t>(dw * dh));
    double worst = 0.0;
    for (int r = 0; r < dh; ++r) {
      for (int col = 0; col < dw; ++col) {
        const Eigen::Vector3d expected = OpenMvsBackProject(c, col, r);
        worst = std::max(worst, (sink.points[static_cast<size_t>(r) * dw + col].point_in_world - expected).norm());
      }
    }
    EXPECT_LT(worst, 1e-6) << dw << "x" << dh;  // metres, at 5.4e6 m coordinates
  }
}

TEST(OpenMvsBlockTest, ListsDepthMapsInNumberOrderAndReadsThem) {
  TempDir dir;
  for (const uint32_t n : {10u, 2u, 10000u}) {
    char name[32];
    std::snprintf(name, sizeof(name), "depth%04u.dmap", n);
    DmapContents c = NadirDmap(10.0 * n, 0, 8, 6, 4, 3, "images\\v" + std::to_string(n) + ".ppm");
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 4; ++col) c.depth.at(r, col) = static_cast<float>(n + 10 * r + col);
    }
    WriteDmap((dir / name).string(), c);
    WritePpm(dir / "images" / ("v" + std::to_string(n) + ".ppm"), 8, 6);
  }
  std::ofstream(dir / "scene.mvs") << "not read";
  std::ofstream(dir / "depth0001.dmap.tmp-1") << "ignored";
  const OpenMvsBlock block(dir.path().string());
  ASSERT_EQ(block.views().size(), 3u);
  EXPECT_EQ(block.views()[0].name, "depth0002.dmap");
  EXPECT_EQ(block.views()[1].name, "depth0010.dmap");
  EXPECT_EQ(block.views()[2].name, "depth10000.dmap");
  for (uint32_t i = 0; i < 3; ++i) EXPECT_EQ(block.views()[i].index, i);
  EXPECT_EQ(block.DepthMapPath(block.views()[1]), (dir / "depth0010.dmap").string());
  EXPECT_EQ(block.ImagePath(block.views()[1]), (dir / "images" / "v10.ppm").string());  // '\' read as '/'
  EXPECT_NEAR(block.views()[1].CenterInWorld().x(), 100.0, 1e-12);

  const View& v = block.views()[1];
  const DepthRasterSize size = block.DepthSize(v);
  EXPECT_EQ(size.width, 4);
  EXPECT_EQ(size.height, 3);
  EXPECT_EQ(block.ReadDepthMap(v).at(2, 3), 33.0f);
  const DepthMap window = block.ReadDepthWindow(v, PixelWindow{1, 3, 2, 4});
  EXPECT_EQ(window.width, 2);
  EXPECT_EQ(window.at(0, 0), 22.0f);
  EXPECT_EQ(window.at(1, 1), 33.0f);
  const RgbImage image = block.ReadImage(v);
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 6);
  EXPECT_EQ(image.at(2, 3, 0), 23);  // R
  EXPECT_EQ(image.at(2, 3, 1), 103);  // G
  EXPECT_EQ(image.at(2, 3, 2), 198);  // B
}

TEST(OpenMvsBlockTest, ImagesMayBeAScaleOfTheHeaderSize) {
  TempDir dir;
  // DensifyPointCloud: the header has the resized image's size (= depth size), the path the full image.
  WriteDmap((dir / "depth0000.dmap").string(), NadirDmap(0, 0, 40, 30, 40, 30, "full.ppm"));
  WritePpm(dir / "full.ppm", 101, 76);  // 2.53x, 75.75 rounded up
  const OpenMvsBlock block(dir.path().string());
  EXPECT_EQ(block.ReadImage(block.views()[0]).width, 101);
  WritePpm(dir / "full.ppm", 30, 40);  // portrait: not this camera's image
  const std::string message = InputErrorOf([&] { block.ReadImage(block.views()[0]); });
  EXPECT_NE(message.find((dir / "full.ppm").string() + ": image is 30x40 but the depth map's camera is 40x30"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("depth0000.dmap"), std::string::npos) << message;
  fs::remove(dir / "full.ppm");
  EXPECT_NE(InputErrorOf([&] { block.ReadImage(block.views()[0]); }).find("missing image file"), std::string::npos);
  std::ofstream(dir / "full.ppm") << "P6\n garbage";
  EXPECT_NE(InputErrorOf([&] { block.ReadImage(block.views()[0]); }).find("cannot decode image"), std::string::npos);
}

TEST(OpenMvsBlockTest, SceneHeightsSampleTheDepthMaps) {
  TempDir dir;
  WriteDmap((dir / "depth0000.dmap").string(), NadirDmap(0, 0, 200, 100, 100, 50, "a.ppm"));
  DmapContents holes = NadirDmap(30, 0, 200, 100, 100, 50, "a.ppm");
  for (int col = 0; col < 50; ++col) {
    for (int r = 0; r < 50; ++r) holes.depth.at(r, col) = 0.0f;  // left half invalid
  }
  WriteDmap((dir / "depth0001.dmap").string(), holes);
  const std::vector<double> z = OpenMvsBlock(dir.path().string()).SceneHeights();
  EXPECT_EQ(z.size(), 16u * 64u + 16u * 32u);
  for (const double h : z) ASSERT_NEAR(h, 5.0, 1e-9);
}

TEST(OpenMvsBlockTest, WriterRoundTrip) {
  TempDir dir;
  const fs::path src = dir / "src";
  DmapContents a = NadirDmap(1.0, 2.0, 16, 12, 8, 6, "a.ppm");
  a.camera.K = {20.0, 0.0, 7.25, 0.0, 21.0, 5.5, 0.0, 0.0, 1.0};
  a.depth.at(0, 0) = 0.0f;
  a.depth.at(1, 1) = -3.0f;
  a.depth.at(2, 2) = std::nanf("");
  WriteDmap((src / "depth0003.dmap").string(), a);
  WriteDmap((src / "depth0005.dmap").string(), NadirDmap(9.0, 2.0, 16, 12, 16, 12, "b.ppm"));
  WritePpm(src / "a.ppm", 16, 12);
  WritePpm(src / "b.ppm", 32, 24);
  const OpenMvsBlock first(src.string());

  const fs::path out = dir / "out";
  WriteOpenMvsBlock(first, out.string());
  EXPECT_TRUE(fs::exists(out / "depth0000.dmap"));
  EXPECT_TRUE(fs::exists(out / "depth0001.dmap"));
  EXPECT_TRUE(fs::exists(out / "images" / "depth0003.dmap.png"));
  const OpenMvsBlock second(out.string());
  ASSERT_EQ(second.views().size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const View& v1 = first.views()[i];
    const View& v2 = second.views()[i];
    EXPECT_EQ(v2.camera.width, v1.camera.width);
    EXPECT_EQ(v2.camera.height, v1.camera.height);
    EXPECT_NEAR(v2.camera.fx, v1.camera.fx, 1e-12);
    EXPECT_NEAR(v2.camera.cx, v1.camera.cx, 1e-12);
    EXPECT_NEAR(v2.camera.cy, v1.camera.cy, 1e-12);
    EXPECT_NEAR((v2.CenterInWorld() - v1.CenterInWorld()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(v2.cam_from_world.rotation.angularDistance(v1.cam_from_world.rotation), 0.0, 1e-12);
    const DepthMap d1 = first.ReadDepthMap(v1), d2 = second.ReadDepthMap(v2);
    ASSERT_EQ(d2.data.size(), d1.data.size());
    for (size_t p = 0; p < d1.data.size(); ++p) {
      EXPECT_EQ(d2.data[p], IsValidDepth(d1.data[p]) ? d1.data[p] : 0.0f) << p;
    }
    const RgbImage i1 = first.ReadImage(v1), i2 = second.ReadImage(v2);
    EXPECT_EQ(i2.width, i1.width);
    EXPECT_EQ(i2.data, i1.data);  // PNG is lossless
  }
  const DmapHeader h = ReadDmapHeader((out / "depth0000.dmap").string());
  EXPECT_EQ(h.image_path, "images/depth0003.dmap.png");
  EXPECT_EQ(h.view_ids, std::vector<uint32_t>{0});
  EXPECT_EQ(h.depth_min, 100.0f);
  EXPECT_EQ(h.depth_max, 100.0f);
  // A second conversion into the same folder would leave stale views: refused.
  EXPECT_THROW(WriteOpenMvsBlock(first, out.string()), Error);
}

TEST(OpenMvsBlockTest, BadFoldersAndCamerasNameTheProblem) {
  TempDir dir;
  EXPECT_NE(InputErrorOf([&] { OpenMvsBlock((dir / "none").string()); }).find("does not exist"), std::string::npos);
  std::ofstream(dir / "scene.mvs") << "x";
  EXPECT_NE(InputErrorOf([&] { OpenMvsBlock(dir.path().string()); })
                .find(dir.path().string() + ": no OpenMVS depth maps"),
            std::string::npos);
  std::ofstream(dir / "depth007.dmap") << "x";
  EXPECT_NE(InputErrorOf([&] { OpenMvsBlock(dir.path().string()); })
                .find((dir / "depth007.dmap").string() + ": looks like an OpenMVS depth map but is not named"),
            std::string::npos);
  fs::remove(dir / "depth007.dmap");

  const std::string path = (dir / "depth0004.dmap").string();
  auto error_with = [&](const DmapContents& c) {
    WriteDmap(path, c);
    const std::string message = InputErrorOf([&] { OpenMvsBlock(dir.path().string()); });
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("(view 0, depth0004.dmap)"), std::string::npos) << message;
    return message;
  };
  DmapContents c = NadirDmap(0, 0, 8, 6, 8, 6, "a.ppm");
  c.camera.K[1] = 0.5;
  EXPECT_NE(error_with(c).find("skew"), std::string::npos);
  c = NadirDmap(0, 0, 8, 6, 8, 6, "a.ppm");
  c.camera.K[0] = 0.0;
  EXPECT_NE(error_with(c).find("focal lengths must be positive"), std::string::npos);
  c = NadirDmap(0, 0, 8, 6, 8, 6, "a.ppm");
  c.camera.K[7] = 1.0;
  EXPECT_NE(error_with(c).find("not upper triangular"), std::string::npos);
  c = NadirDmap(0, 0, 8, 6, 8, 6, "a.ppm");
  c.camera.R = {1, 0, 0, 0, 1, 0, 0, 0, -1};  // a reflection
  EXPECT_NE(error_with(c).find("not a rotation"), std::string::npos);
  c = NadirDmap(0, 0, 8, 6, 8, 6, "a.ppm");
  c.camera.R[0] = 1.01;
  EXPECT_NE(error_with(c).find("not a rotation"), std::string::npos);
  c = NadirDmap(0, 0, 8, 6, 8, 6, "a.ppm");
  c.camera.C[2] = std::nan("");
  EXPECT_NE(error_with(c).find("not finite"), std::string::npos);
  c = NadirDmap(0, 0, 8, 6, 8, 6, "");
  EXPECT_NE(error_with(c).find("names no image"), std::string::npos);
  // A corrupt file among good ones fails the whole block, naming it.
  WriteDmap(path, NadirDmap(0, 0, 8, 6, 8, 6, "a.ppm"));
  std::ofstream(dir / "depth0009.dmap") << "DR";
  EXPECT_NE(InputErrorOf([&] { OpenMvsBlock(dir.path().string()); })
                .find((dir / "depth0009.dmap").string() + ": truncated depth map header"),
            std::string::npos);
}

}  // namespace
}  // namespace sacfuse
