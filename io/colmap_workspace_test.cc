#include "io/colmap_workspace.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/colmap_array.h"
#include "tests/support/log_capture.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using sacfuse::testing::TempDir;

// --- A minimal PNG encoder (stored deflate blocks), so the test needs no image library headers. ------------

uint32_t Crc32(const std::string& bytes) {
  uint32_t crc = 0xffffffffu;
  for (const char ch : bytes) {
    crc ^= static_cast<uint8_t>(ch);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string BigEndian32(uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

std::string PngChunk(const std::string& type, const std::string& data) {
  return BigEndian32(static_cast<uint32_t>(data.size())) + type + data + BigEndian32(Crc32(type + data));
}

// `pixels` is row-major with `channels` (1 = gray, 3 = RGB) bytes per pixel.
std::string EncodePng(int width, int height, int channels, const std::vector<uint8_t>& pixels) {
  std::string raw;
  for (int row = 0; row < height; ++row) {
    raw += '\0';  // filter: none
    raw.append(reinterpret_cast<const char*>(pixels.data()) + static_cast<size_t>(row) * width * channels,
               static_cast<size_t>(width) * channels);
  }
  std::string z = "\x78\x01";
  for (size_t pos = 0; pos == 0 || pos < raw.size(); pos += 65535) {
    const size_t n = std::min<size_t>(65535, raw.size() - pos);
    const bool last = pos + n >= raw.size();
    z += static_cast<char>(last ? 1 : 0);
    z += static_cast<char>(n & 0xff);
    z += static_cast<char>(n >> 8);
    z += static_cast<char>(~n & 0xff);
    z += static_cast<char>((~n >> 8) & 0xff);
    z += raw.substr(pos, n);
  }
  uint32_t a = 1, b = 0;
  for (const char ch : raw) {
    a = (a + static_cast<uint8_t>(ch)) % 65521;
    b = (b + a) % 65521;
  }
  z += BigEndian32((b << 16) | a);
  const std::string ihdr = BigEndian32(width) + BigEndian32(height) + std::string{8, channels == 3 ? '\2' : '\0'} +
                           std::string(3, '\0');
  return std::string("\x89PNG\r\n\x1a\n", 8) + PngChunk("IHDR", ihdr) + PngChunk("IDAT", z) + PngChunk("IEND", "");
}

void WriteFile(const std::filesystem::path& path, const std::string& contents) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << contents;
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

template <typename Fn>
void ExpectInputError(Fn fn, const std::vector<std::string>& parts) {
  try {
    fn();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    for (const std::string& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

// --- The test workspace ------------------------------------------------------------------------------------
// Three 8x6 images: nadir/img0.png (PINHOLE), nadir/img1.png (SIMPLE_PINHOLE), oblique/img2.png (OPENCV, zero
// distortion). Depth value at (row, col) = 100 + view*10 + row + col/10; normal = (view, row, col).
// img1's maps are half size (4x3), as with max_image_size. fusion.cfg lists img2 then img0.
const char* const kNames[] = {"nadir/img0.png", "nadir/img1.png", "oblique/img2.png"};

Raster<float> DepthFor(int view, int w, int h) {
  Raster<float> d(w, h, 1);
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) d.at(row, col) = 100.0f + view * 10.0f + row + col / 10.0f;
  }
  return d;
}

Raster<float> NormalFor(int view, int w, int h) {
  Raster<float> n(w, h, 3);
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) {
      n.at(row, col, 0) = static_cast<float>(view);
      n.at(row, col, 1) = static_cast<float>(row);
      n.at(row, col, 2) = static_cast<float>(col);
    }
  }
  return n;
}

ColmapModel MakeModel() {
  ColmapModel m;
  m.cameras[1] = ColmapCamera{1, "PINHOLE", 8, 6, {10.0, 11.0, 4.0, 3.5}};
  m.cameras[2] = ColmapCamera{2, "SIMPLE_PINHOLE", 8, 6, {12.0, 4.25, 3.0}};
  m.cameras[3] = ColmapCamera{3, "OPENCV", 8, 6, {13.0, 14.0, 3.75, 2.5, 0.0, 0.0, 0.0, 0.0}};
  for (uint32_t i = 0; i < 3; ++i) {
    ColmapImage img;
    img.image_id = 10 + i;
    img.camera_id = 1 + i;
    img.name = kNames[i];
    img.cam_from_world_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * (i + 1), Eigen::Vector3d::UnitZ()));
    img.cam_from_world_translation = {390000.5 + i, 5705000.25, 900.0};
    m.images.push_back(img);
  }
  return m;
}

void BuildWorkspace(const std::filesystem::path& dir, bool text_model = false) {
  const ColmapModel model = MakeModel();
  std::filesystem::create_directories(dir / "sparse");
  text_model ? WriteColmapModelText(model, (dir / "sparse").string())
             : WriteColmapModelBinary(model, (dir / "sparse").string());
  for (int v = 0; v < 3; ++v) {
    const int w = v == 1 ? 4 : 8, h = v == 1 ? 3 : 6;
    for (const char* type : {"geometric", "photometric"}) {
      const std::string suffix = std::string(".") + type + ".bin";
      const float offset = std::string(type) == "geometric" ? 0.0f : 0.5f;
      Raster<float> depth = DepthFor(v, w, h);
      for (float& d : depth.data) d += offset;
      WriteColmapArray((dir / "stereo/depth_maps" / (std::string(kNames[v]) + suffix)).string(), depth);
      WriteColmapArray((dir / "stereo/normal_maps" / (std::string(kNames[v]) + suffix)).string(), NormalFor(v, w, h));
    }
    // Colour image: R = 10*col, G = 20*row, B = 200 + view. img1 is grayscale: value 30*row + col.
    std::vector<uint8_t> pixels;
    for (int row = 0; row < 6; ++row) {
      for (int col = 0; col < 8; ++col) {
        if (v == 1) {
          pixels.push_back(static_cast<uint8_t>(30 * row + col));
        } else {
          pixels.insert(pixels.end(), {static_cast<uint8_t>(10 * col), static_cast<uint8_t>(20 * row),
                                       static_cast<uint8_t>(200 + v)});
        }
      }
    }
    WriteFile(dir / "images" / kNames[v], EncodePng(8, 6, v == 1 ? 1 : 3, pixels));
  }
  WriteFile(dir / "stereo/fusion.cfg", "oblique/img2.png\n  nadir/img0.png  \r\n\n");
}

TEST(ColmapWorkspaceTest, ViewsFollowFusionCfg) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  const ColmapWorkspace ws(tmp.path().string(), ColmapDepthType::kGeometric);
  ASSERT_EQ(ws.views().size(), 2u);
  const View& v0 = ws.views()[0];
  const View& v1 = ws.views()[1];
  EXPECT_EQ(v0.index, 0u);
  EXPECT_EQ(v0.name, "oblique/img2.png");
  EXPECT_EQ(v1.index, 1u);
  EXPECT_EQ(v1.name, "nadir/img0.png");
  // OPENCV with zero distortion -> fx, fy, cx, cy.
  EXPECT_EQ(v0.camera.width, 8);
  EXPECT_EQ(v0.camera.height, 6);
  EXPECT_EQ(v0.camera.fx, 13.0);
  EXPECT_EQ(v0.camera.fy, 14.0);
  EXPECT_EQ(v0.camera.cx, 3.75);
  EXPECT_EQ(v0.camera.cy, 2.5);
  EXPECT_EQ(v1.camera.fx, 10.0);
  EXPECT_EQ(v1.camera.fy, 11.0);
  EXPECT_EQ(v1.camera.cx, 4.0);
  EXPECT_EQ(v1.camera.cy, 3.5);
  // Pose from qvec/tvec: the camera centre is -R^T t.
  const ColmapImage& img2 = ws.model().images[2];
  EXPECT_EQ(v0.cam_from_world.translation, img2.cam_from_world_translation);
  EXPECT_NEAR(v0.cam_from_world.rotation.angularDistance(img2.cam_from_world_rotation), 0.0, 1e-15);
  const Eigen::Vector3d centre = -(img2.cam_from_world_rotation.conjugate() * img2.cam_from_world_translation);
  EXPECT_LT((v0.CenterInWorld() - centre).norm(), 1e-9);
  EXPECT_EQ(ws.model().images.size(), 3u);
}

TEST(ColmapWorkspaceTest, WithoutFusionCfgUsesModelOrder) {
  TempDir tmp;
  BuildWorkspace(tmp.path(), /*text_model=*/true);
  std::filesystem::remove(tmp / "stereo/fusion.cfg");
  const ColmapWorkspace ws(tmp.path().string(), ColmapDepthType::kGeometric);
  ASSERT_EQ(ws.views().size(), 3u);
  for (uint32_t i = 0; i < 3; ++i) {
    EXPECT_EQ(ws.views()[i].index, i);
    EXPECT_EQ(ws.views()[i].name, kNames[i]);
  }
  // SIMPLE_PINHOLE: f, cx, cy.
  const PinholeCamera& c = ws.views()[1].camera;
  EXPECT_EQ(c.fx, 12.0);
  EXPECT_EQ(c.fy, 12.0);
  EXPECT_EQ(c.cx, 4.25);
  EXPECT_EQ(c.cy, 3.0);
}

TEST(ColmapWorkspaceTest, Paths) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  const std::string dir = tmp.path().string();
  const ColmapWorkspace geo(dir, ColmapDepthType::kGeometric);
  const View& v = geo.views()[1];
  EXPECT_EQ(geo.dir(), dir);
  EXPECT_EQ(geo.ImagePath(v), dir + "/images/nadir/img0.png");
  EXPECT_EQ(geo.DepthMapPath(v), dir + "/stereo/depth_maps/nadir/img0.png.geometric.bin");
  EXPECT_EQ(geo.NormalMapPath(v), dir + "/stereo/normal_maps/nadir/img0.png.geometric.bin");
  const ColmapWorkspace photo(dir, ColmapDepthType::kPhotometric);
  EXPECT_EQ(photo.DepthMapPath(v), dir + "/stereo/depth_maps/nadir/img0.png.photometric.bin");
  EXPECT_EQ(photo.NormalMapPath(v), dir + "/stereo/normal_maps/nadir/img0.png.photometric.bin");
  EXPECT_EQ(photo.ReadDepthMap(photo.views()[0]).at(0, 0), 120.5f);
}

TEST(ColmapWorkspaceTest, ReadsRasters) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  std::filesystem::remove(tmp / "stereo/fusion.cfg");
  const ColmapWorkspace ws(tmp.path().string(), ColmapDepthType::kGeometric);
  const View& v2 = ws.views()[2];
  const DepthMap depth = ws.ReadDepthMap(v2);
  ASSERT_EQ(depth.width, 8);
  ASSERT_EQ(depth.height, 6);
  ASSERT_EQ(depth.channels, 1);
  EXPECT_EQ(depth.at(3, 5), 100.0f + 20.0f + 3.0f + 0.5f);
  // Rows alone (co-registration's decimated read): the same values as the whole map's rows.
  const DepthMap rows = ws.ReadDepthRows(v2, {3, 0});
  ASSERT_EQ(rows.width, 8);
  ASSERT_EQ(rows.height, 2);
  for (int col = 0; col < 8; ++col) {
    EXPECT_EQ(rows.at(0, col), depth.at(3, col));
    EXPECT_EQ(rows.at(1, col), depth.at(0, col));
  }
  const NormalMap normal = ws.ReadNormalMap(v2);
  ASSERT_EQ(normal.channels, 3);
  EXPECT_EQ(normal.at(4, 7, 0), 2.0f);
  EXPECT_EQ(normal.at(4, 7, 1), 4.0f);
  EXPECT_EQ(normal.at(4, 7, 2), 7.0f);
  const RgbImage rgb = ws.ReadImage(v2);
  ASSERT_EQ(rgb.width, 8);
  ASSERT_EQ(rgb.height, 6);
  ASSERT_EQ(rgb.channels, 3);
  EXPECT_EQ(rgb.at(5, 7, 0), 70);   // R
  EXPECT_EQ(rgb.at(5, 7, 1), 100);  // G
  EXPECT_EQ(rgb.at(5, 7, 2), 202);  // B
  // Grayscale image -> three equal channels.
  const RgbImage gray = ws.ReadImage(ws.views()[1]);
  ASSERT_EQ(gray.channels, 3);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(gray.at(2, 3, c), 63);
  // Half-size maps of img1 (4x3 for an 8x6 image) are accepted as they are.
  const DepthMap half = ws.ReadDepthMap(ws.views()[1]);
  EXPECT_EQ(half.width, 4);
  EXPECT_EQ(half.height, 3);
  EXPECT_EQ(half.at(2, 3), 100.0f + 10.0f + 2.0f + 0.3f);
  EXPECT_EQ(ws.ReadNormalMap(ws.views()[1]).width, 4);
}

TEST(ColmapWorkspaceTest, MisSizedOrMisShapedMapsAreRejected) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  const ColmapWorkspace ws(tmp.path().string(), ColmapDepthType::kGeometric);
  const View& v = ws.views()[1];  // nadir/img0.png, 8x6
  WriteColmapArray(ws.DepthMapPath(v), DepthFor(0, 8, 3));  // wrong aspect
  ExpectInputError([&] { ws.ReadDepthMap(v); }, {ws.DepthMapPath(v), "nadir/img0.png", "8x3"});
  ExpectInputError([&] { ws.ReadDepthRows(v, {0}); }, {ws.DepthMapPath(v), "nadir/img0.png", "8x3"});
  WriteColmapArray(ws.DepthMapPath(v), DepthFor(0, 16, 12));  // larger than the image
  ExpectInputError([&] { ws.ReadDepthMap(v); }, {ws.DepthMapPath(v), "nadir/img0.png"});
  WriteColmapArray(ws.DepthMapPath(v), DepthFor(0, 5, 4));  // 0.625 / 0.667: within 1 px of rounding
  EXPECT_EQ(ws.ReadDepthMap(v).width, 5);
  WriteColmapArray(ws.DepthMapPath(v), NormalFor(0, 8, 6));  // 3 channels where 1 is expected
  ExpectInputError([&] { ws.ReadDepthMap(v); }, {ws.DepthMapPath(v), "nadir/img0.png", "3 channels"});
  ExpectInputError([&] { ws.ReadDepthRows(v, {0}); }, {ws.DepthMapPath(v), "nadir/img0.png", "3 channels"});
  WriteColmapArray(ws.NormalMapPath(v), DepthFor(0, 8, 6));
  ExpectInputError([&] { ws.ReadNormalMap(v); }, {ws.NormalMapPath(v), "nadir/img0.png", "1 channels"});
  WriteFile(ws.DepthMapPath(v), "8&6&1&");  // truncated: the image is named too
  ExpectInputError([&] { ws.ReadDepthMap(v); }, {ws.DepthMapPath(v), "nadir/img0.png", "truncated"});
  ExpectInputError([&] { ws.ReadDepthRows(v, {0}); }, {ws.DepthMapPath(v), "nadir/img0.png", "truncated"});
}

TEST(ColmapWorkspaceTest, MissingOrBadFilesNameFileAndImage) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  const ColmapWorkspace ws(tmp.path().string(), ColmapDepthType::kGeometric);
  const View& v = ws.views()[0];  // oblique/img2.png
  std::filesystem::remove(ws.DepthMapPath(v));
  ExpectInputError([&] { ws.ReadDepthMap(v); }, {ws.DepthMapPath(v), "oblique/img2.png", "missing"});
  std::filesystem::remove(ws.NormalMapPath(v));
  ExpectInputError([&] { ws.ReadNormalMap(v); }, {ws.NormalMapPath(v), "oblique/img2.png", "missing"});
  WriteFile(ws.ImagePath(v), "not an image");
  ExpectInputError([&] { ws.ReadImage(v); }, {ws.ImagePath(v), "oblique/img2.png"});
  std::filesystem::remove(ws.ImagePath(v));
  ExpectInputError([&] { ws.ReadImage(v); }, {ws.ImagePath(v), "oblique/img2.png", "missing"});
  WriteFile(ws.ImagePath(v), EncodePng(4, 3, 1, std::vector<uint8_t>(12, 0)));
  ExpectInputError([&] { ws.ReadImage(v); }, {ws.ImagePath(v), "oblique/img2.png", "4x3"});
}

// Real workspaces as the matcher leaves them: a view without a depth map is left out with a warning naming the
// file (COLMAP's stereo_fusion ignores it too); a workspace with photometric maps only, or none, names the fix.
TEST(ColmapWorkspaceTest, ViewsWithoutDepthMapsAreLeftOutOrNameTheFix) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  const std::string dir = tmp.path().string();
  const std::filesystem::path maps = tmp / "stereo/depth_maps";
  std::filesystem::remove(maps / "oblique/img2.png.geometric.bin");
  {
    testing::LogCapture log;
    const ColmapWorkspace ws(dir, ColmapDepthType::kGeometric);
    ASSERT_EQ(ws.views().size(), 1u);
    EXPECT_EQ(ws.views()[0].name, "nadir/img0.png");
    EXPECT_EQ(ws.views()[0].index, 0u);
    EXPECT_EQ(ws.ReadDepthMap(ws.views()[0]).at(0, 0), 100.0f);
    EXPECT_NE(log.text().find("oblique/img2.png.geometric.bin: missing: image \"oblique/img2.png\" has no geometric "
                              "depth map and is left out (1 of 2 images are fused)"),
              std::string::npos)
        << log.text();
    // The photometric maps are all there.
    EXPECT_EQ(ColmapWorkspace(dir, ColmapDepthType::kPhotometric).views().size(), 2u);
  }
  std::filesystem::remove(maps / "nadir/img0.png.geometric.bin");
  ExpectInputError([&] { ColmapWorkspace(dir, ColmapDepthType::kGeometric); },
                   {"no geometric depth map for any of the 2 images", "it has photometric ones for 2 of them",
                    "geom_consistency false", "set input.depth_type: photometric"});
  for (const char* name : {"oblique/img2.png", "nadir/img0.png"}) {
    std::filesystem::remove(maps / (std::string(name) + ".photometric.bin"));
  }
  ExpectInputError([&] { ColmapWorkspace(dir, ColmapDepthType::kPhotometric); },
                   {"no photometric depth map for any of the 2 images", "run the dense matcher first"});
}

TEST(ColmapWorkspaceTest, DistortedCamerasAreRejected) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  ColmapModel model = MakeModel();
  model.cameras[3].params[4] = 0.01;  // OPENCV k1
  WriteColmapModelBinary(model, (tmp / "sparse").string());
  ExpectInputError([&] { ColmapWorkspace(tmp.path().string(), ColmapDepthType::kGeometric); },
                   {"cameras.bin", "camera_id 3", "OPENCV", "oblique/img2.png", "undistorted", "image_undistorter"});
  // Zero-distortion variants of other models are pinhole.
  model.cameras[3] = ColmapCamera{3, "SIMPLE_RADIAL", 8, 6, {9.0, 4.0, 3.0, 0.0}};
  model.cameras[2] = ColmapCamera{2, "FULL_OPENCV", 8, 6, {9.0, 9.5, 4.0, 3.0, 0, 0, 0, 0, 0, 0, 0, 0}};
  model.cameras[1] = ColmapCamera{1, "RADIAL", 8, 6, {8.0, 4.0, 3.0, 0.0, 0.0}};
  WriteColmapModelText(model, (tmp / "sparse").string());
  std::filesystem::remove(tmp / "sparse/cameras.bin");
  std::filesystem::remove(tmp / "stereo/fusion.cfg");
  const ColmapWorkspace ws(tmp.path().string(), ColmapDepthType::kGeometric);
  EXPECT_EQ(ws.views()[2].camera.fx, 9.0);
  EXPECT_EQ(ws.views()[2].camera.fy, 9.0);
  EXPECT_EQ(ws.views()[1].camera.fy, 9.5);
  EXPECT_EQ(ws.views()[0].camera.cx, 4.0);
  model.cameras[1].params[4] = -0.2;  // RADIAL k2
  WriteColmapModelText(model, (tmp / "sparse").string());
  ExpectInputError([&] { ColmapWorkspace(tmp.path().string(), ColmapDepthType::kGeometric); },
                   {"cameras.txt", "RADIAL", "nadir/img0.png", "undistorted"});
  // A fisheye model is not pinhole even with zero distortion.
  model.cameras[1] = ColmapCamera{1, "OPENCV_FISHEYE", 8, 6, {9.0, 9.0, 4.0, 3.0, 0, 0, 0, 0}};
  WriteColmapModelText(model, (tmp / "sparse").string());
  ExpectInputError([&] { ColmapWorkspace(tmp.path().string(), ColmapDepthType::kGeometric); },
                   {"cameras.txt", "OPENCV_FISHEYE", "fisheye"});
}

TEST(ColmapWorkspaceTest, FusionCfgNameNotInModel) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  WriteFile(tmp / "stereo/fusion.cfg", "nadir/img0.png\nnadir/img9.png\n");
  ExpectInputError([&] { ColmapWorkspace(tmp.path().string(), ColmapDepthType::kGeometric); },
                   {"fusion.cfg", "line 2", "nadir/img9.png"});
  WriteFile(tmp / "stereo/fusion.cfg", "nadir/img0.png\nnadir/img0.png\n");
  ExpectInputError([&] { ColmapWorkspace(tmp.path().string(), ColmapDepthType::kGeometric); },
                   {"fusion.cfg", "line 2", "twice"});
}

TEST(ColmapWorkspaceTest, MatchingPartnersFromPatchMatchCfg) {
  TempDir tmp;
  BuildWorkspace(tmp.path());  // fuses oblique/img2.png (view 0) and nadir/img0.png (view 1)
  const auto partners = [&] {
    const ColmapWorkspace ws(tmp.path().string(), ColmapDepthType::kGeometric);
    return std::vector<std::vector<uint32_t>>{ws.views()[0].matching_partners, ws.views()[1].matching_partners};
  };
  using Lists = std::vector<std::vector<uint32_t>>;
  // Absent: unknown.
  EXPECT_EQ(partners(), (Lists{{}, {}}));
  // Named sources (img1 is not fused): img0 lists img2, so both are partners.
  WriteFile(tmp / "stereo/patch-match.cfg", "nadir/img0.png\noblique/img2.png, nadir/img1.png\n");
  EXPECT_EQ(partners(), (Lists{{1}, {0}}));
  // COLMAP's own "__auto__, 20": unknown.
  WriteColmapStereoConfigs(tmp.path().string(), {"oblique/img2.png", "nadir/img0.png"});
  EXPECT_EQ(partners(), (Lists{{}, {}}));
  // Malformed: the views are still fused, without partners, and a warning names the file and line.
  WriteFile(tmp / "stereo/patch-match.cfg", "nadir/img0.png\noblique/img2.png\nnadir/img1.png\n");
  sacfuse::testing::LogCapture log;
  EXPECT_EQ(partners(), (Lists{{}, {}}));
  EXPECT_NE(log.text().find("patch-match.cfg: line 3: image \"nadir/img1.png\" has no sources line"),
            std::string::npos)
      << log.text();
  EXPECT_NE(log.text().find("matching partners are unknown"), std::string::npos);
}

TEST(ColmapWorkspaceTest, MissingSparseModel) {
  TempDir tmp;
  BuildWorkspace(tmp.path());
  std::filesystem::remove(tmp / "sparse/images.bin");
  ExpectInputError([&] { ColmapWorkspace(tmp.path().string(), ColmapDepthType::kGeometric); },
                   {"sparse/images.bin", "missing"});
}

TEST(ColmapWorkspaceTest, WritesStereoConfigs) {
  TempDir tmp;
  WriteColmapStereoConfigs(tmp.path().string(), {"a/x.jpg", "b.jpg"});
  EXPECT_EQ(ReadFile(tmp / "stereo/fusion.cfg"), "a/x.jpg\nb.jpg\n");
  EXPECT_EQ(ReadFile(tmp / "stereo/patch-match.cfg"), "a/x.jpg\n__auto__, 20\nb.jpg\n__auto__, 20\n");
  EXPECT_THROW(WriteColmapStereoConfigs(tmp.path().string(), {"bad\nname"}), Error);
  EXPECT_THROW(WriteColmapStereoConfigs(tmp.path().string(), {"bad,name"}), Error);
  // Named sources (a view without any gets COLMAP's automatic choice); they read back as written.
  WriteColmapStereoConfigs(tmp.path().string(), {"a/x.jpg", "b.jpg", "c.jpg"}, {{"b.jpg", "c.jpg"}, {"a/x.jpg"}, {}});
  EXPECT_EQ(ReadFile(tmp / "stereo/patch-match.cfg"), "a/x.jpg\nb.jpg, c.jpg\nb.jpg\na/x.jpg\nc.jpg\n__auto__, 20\n");
  EXPECT_THROW(WriteColmapStereoConfigs(tmp.path().string(), {"a/x.jpg"}, {{}, {}}), Error);
}

}  // namespace
}  // namespace sacfuse
