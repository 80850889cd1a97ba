#include "io/colmap_model.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using sacfuse::testing::TempDir;

void WriteFile(const std::filesystem::path& path, const std::string& contents) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << contents;
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Expects ReadColmapModel(dir) to throw an InputError whose message contains every one of `parts`.
void ExpectModelError(const std::filesystem::path& dir, const std::vector<std::string>& parts) {
  try {
    ReadColmapModel(dir.string());
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    for (const std::string& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

constexpr char kCamerasTxt[] =
    "# Camera list with one line of data per camera:\n"
    "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
    "# Number of cameras: 2\n"
    "1 SIMPLE_PINHOLE 3072 2304 2559.81 1536 1152\n"
    "2 PINHOLE 6000 4000 8000.5 8001.25 3000 2000.75\n";

constexpr char kImagesTxt[] =
    "# Image list with two lines of data per image:\n"
    "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
    "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
    "# Number of images: 2, mean observations per image: 1\n"
    "1 0.851773 0.0165051 0.503764 -0.142941 -0.737434 1.02973 3.74354 1 P1180141.JPG\n"
    "2362.39 248.498 58396 1784.7 268.254 -1\n"
    "7 1 0 0 0 390000.5 5705000.25 900 2 cam1/IMG_0001.jpg\n"
    "\n";

constexpr char kPoints3DTxt[] =
    "# 3D point list with one line of data per point:\n"
    "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
    "# Number of points: 1, mean track length: 2\n"
    "58396 1.67241 0.292931 0.609726 115 121 122 1.33927 1 0 7 3\n";

void WriteHandMadeText(const std::filesystem::path& dir) {
  WriteFile(dir / "cameras.txt", kCamerasTxt);
  WriteFile(dir / "images.txt", kImagesTxt);
  WriteFile(dir / "points3D.txt", kPoints3DTxt);
}

TEST(ColmapModelTest, ParsesHandWrittenText) {
  TempDir tmp;
  WriteHandMadeText(tmp.path());
  const ColmapModel model = ReadColmapModel(tmp.path().string());

  ASSERT_EQ(model.cameras.size(), 2u);
  const ColmapCamera& c1 = model.cameras.at(1);
  EXPECT_EQ(c1.model, "SIMPLE_PINHOLE");
  EXPECT_EQ(c1.width, 3072u);
  EXPECT_EQ(c1.height, 2304u);
  EXPECT_EQ(c1.params, (std::vector<double>{2559.81, 1536, 1152}));
  EXPECT_EQ(model.cameras.at(2).params, (std::vector<double>{8000.5, 8001.25, 3000, 2000.75}));

  ASSERT_EQ(model.images.size(), 2u);
  const ColmapImage& i1 = model.images[0];
  EXPECT_EQ(i1.image_id, 1u);
  EXPECT_EQ(i1.camera_id, 1u);
  EXPECT_EQ(i1.name, "P1180141.JPG");
  // The file's quaternion is (almost) unit; it is normalised on read.
  const double n = std::sqrt(0.851773 * 0.851773 + 0.0165051 * 0.0165051 + 0.503764 * 0.503764 +
                             0.142941 * 0.142941);
  EXPECT_NEAR(i1.cam_from_world_rotation.w(), 0.851773 / n, 1e-15);
  EXPECT_NEAR(i1.cam_from_world_rotation.z(), -0.142941 / n, 1e-15);
  EXPECT_EQ(i1.cam_from_world_translation, Eigen::Vector3d(-0.737434, 1.02973, 3.74354));
  ASSERT_EQ(i1.points2D.size(), 2u);
  EXPECT_EQ(i1.points2D[0].xy, Eigen::Vector2d(2362.39, 248.498));
  EXPECT_EQ(i1.points2D[0].point3D_id, 58396u);
  EXPECT_EQ(i1.points2D[1].point3D_id, UINT64_MAX);

  const ColmapImage& i7 = model.images[1];
  EXPECT_EQ(i7.image_id, 7u);
  EXPECT_EQ(i7.name, "cam1/IMG_0001.jpg");
  EXPECT_EQ(i7.cam_from_world_translation, Eigen::Vector3d(390000.5, 5705000.25, 900));
  EXPECT_TRUE(i7.points2D.empty());

  ASSERT_EQ(model.points3D.size(), 1u);
  const ColmapPoint3D& p = model.points3D.at(58396);
  EXPECT_EQ(p.xyz, Eigen::Vector3d(1.67241, 0.292931, 0.609726));
  EXPECT_EQ(p.rgb, (std::array<uint8_t, 3>{115, 121, 122}));
  EXPECT_EQ(p.error, 1.33927);
  ASSERT_EQ(p.track.size(), 2u);
  EXPECT_EQ(p.track[1].image_id, 7u);
  EXPECT_EQ(p.track[1].point2D_idx, 3u);
}

ColmapModel MakeModel() {
  ColmapModel m;
  // One camera of every model, with distinct parameter values.
  for (int id = 0; id <= 11; ++id) {
    ColmapCamera cam;
    cam.camera_id = 100 + id;
    cam.model = ColmapCameraModelName(id);
    cam.width = 4000 + id;
    cam.height = 3000 + id;
    for (int k = 0; k < ColmapCameraModelNumParams(cam.model); ++k) cam.params.push_back(1000.0 / 3.0 + k * 0.1 + id);
    m.cameras[cam.camera_id] = cam;
  }
  ColmapImage a;
  a.image_id = 5;
  a.camera_id = 101;
  a.name = "nadir/IMG 0001.JPG";  // sub-folder and a space
  a.cam_from_world_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  a.cam_from_world_translation = {-390000.5 / 3.0, 5705000.25, 900.125};
  a.points2D = {{{10.25, 20.5}, 42}, {{1.0 / 3.0, 2.0 / 7.0}, UINT64_MAX}};
  ColmapImage b;
  b.image_id = 2;
  b.camera_id = 100;
  b.name = "b.png";
  m.images = {a, b};
  ColmapPoint3D p;
  p.point3D_id = 42;
  p.xyz = {390001.1, 5705002.2, 123.456789};
  p.rgb = {1, 128, 255};
  p.error = 0.1;
  p.track = {{5, 0}, {2, 17}};
  m.points3D[42] = p;
  ColmapPoint3D q;
  q.point3D_id = 1ull << 40;
  m.points3D[q.point3D_id] = q;
  return m;
}

void ExpectModelsEqual(const ColmapModel& a, const ColmapModel& b) {
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (const auto& [id, cam] : a.cameras) {
    const ColmapCamera& other = b.cameras.at(id);
    EXPECT_EQ(cam.camera_id, other.camera_id);
    EXPECT_EQ(cam.model, other.model);
    EXPECT_EQ(cam.width, other.width);
    EXPECT_EQ(cam.height, other.height);
    EXPECT_EQ(cam.params, other.params);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) {
    const ColmapImage &x = a.images[i], &y = b.images[i];
    EXPECT_EQ(x.image_id, y.image_id);
    EXPECT_EQ(x.camera_id, y.camera_id);
    EXPECT_EQ(x.name, y.name);
    EXPECT_NEAR(x.cam_from_world_rotation.angularDistance(y.cam_from_world_rotation), 0.0, 1e-15);
    EXPECT_EQ(x.cam_from_world_translation, y.cam_from_world_translation);
    ASSERT_EQ(x.points2D.size(), y.points2D.size());
    for (size_t k = 0; k < x.points2D.size(); ++k) {
      EXPECT_EQ(x.points2D[k].xy, y.points2D[k].xy);
      EXPECT_EQ(x.points2D[k].point3D_id, y.points2D[k].point3D_id);
    }
  }
  ASSERT_EQ(a.points3D.size(), b.points3D.size());
  for (const auto& [id, p] : a.points3D) {
    const ColmapPoint3D& q = b.points3D.at(id);
    EXPECT_EQ(p.xyz, q.xyz);
    EXPECT_EQ(p.rgb, q.rgb);
    EXPECT_EQ(p.error, q.error);
    ASSERT_EQ(p.track.size(), q.track.size());
    for (size_t k = 0; k < p.track.size(); ++k) {
      EXPECT_EQ(p.track[k].image_id, q.track[k].image_id);
      EXPECT_EQ(p.track[k].point2D_idx, q.track[k].point2D_idx);
    }
  }
}

TEST(ColmapModelTest, BinaryRoundTrip) {
  TempDir tmp;
  const ColmapModel model = MakeModel();
  WriteColmapModelBinary(model, tmp.path().string());
  EXPECT_FALSE(std::filesystem::exists(tmp / "cameras.txt"));
  ExpectModelsEqual(model, ReadColmapModel(tmp.path().string()));
}

TEST(ColmapModelTest, TextRoundTrip) {
  TempDir tmp;
  const ColmapModel model = MakeModel();
  WriteColmapModelText(model, tmp.path().string());
  EXPECT_FALSE(std::filesystem::exists(tmp / "cameras.bin"));
  const std::string cameras = ReadFile(tmp / "cameras.txt");
  EXPECT_EQ(cameras.rfind("# Camera list with one line of data per camera:\n", 0), 0u);
  EXPECT_NE(cameras.find("# Number of cameras: 12\n"), std::string::npos);
  // Image b has no points: its POINTS2D line is empty, as COLMAP writes it.
  EXPECT_NE(ReadFile(tmp / "images.txt").find(" 100 b.png\n\n"), std::string::npos);
  ExpectModelsEqual(model, ReadColmapModel(tmp.path().string()));
}

TEST(ColmapModelTest, HandWrittenTextSurvivesTextAndBinaryRewrite) {
  TempDir tmp;
  WriteHandMadeText(tmp / "in");
  const ColmapModel model = ReadColmapModel((tmp / "in").string());
  WriteColmapModelText(model, (tmp / "txt").string());
  WriteColmapModelBinary(model, (tmp / "bin").string());
  ExpectModelsEqual(model, ReadColmapModel((tmp / "txt").string()));
  ExpectModelsEqual(model, ReadColmapModel((tmp / "bin").string()));
}

std::string LittleEndianBytes(uint64_t v, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
  return s;
}

TEST(ColmapModelTest, CameraBinaryBytesMatchColmapLayout) {
  TempDir tmp;
  ColmapModel model;
  model.cameras[7] = ColmapCamera{7, "PINHOLE", 640, 480, {500.0, 501.0, 320.0, 240.0}};
  WriteColmapModelBinary(model, tmp.path().string());
  const std::string expected = std::string("\x01\0\0\0\0\0\0\0", 8) +  // u64 number of cameras
                               std::string("\x07\0\0\0", 4) +          // u32 camera_id
                               std::string("\x01\0\0\0", 4) +          // i32 model_id (PINHOLE)
                               std::string("\x80\x02\0\0\0\0\0\0", 8) +  // u64 width 640
                               std::string("\xe0\x01\0\0\0\0\0\0", 8) +  // u64 height 480
                               std::string("\0\0\0\0\0\x40\x7f\x40", 8) +  // f64 500
                               std::string("\0\0\0\0\0\x50\x7f\x40", 8) +  // f64 501
                               std::string("\0\0\0\0\0\0\x74\x40", 8) +    // f64 320
                               std::string("\0\0\0\0\0\0\x6e\x40", 8);     // f64 240
  EXPECT_EQ(ReadFile(tmp / "cameras.bin"), expected);
  EXPECT_EQ(ReadFile(tmp / "images.bin"), std::string(8, '\0'));
  EXPECT_EQ(ReadFile(tmp / "points3D.bin"), std::string(8, '\0'));
}

TEST(ColmapModelTest, ReadsHandBuiltImageAndPointBytes) {
  TempDir tmp;
  WriteFile(tmp / "cameras.bin", LittleEndianBytes(1, 8) + LittleEndianBytes(3, 4) + LittleEndianBytes(0, 4) +
                                      LittleEndianBytes(10, 8) + LittleEndianBytes(8, 8) +
                                      std::string("\0\0\0\0\0\0\x24\x40", 8) +  // f = 10
                                      std::string("\0\0\0\0\0\0\x14\x40", 8) +  // cx = 5
                                      std::string("\0\0\0\0\0\0\x10\x40", 8));  // cy = 4
  const std::string one("\0\0\0\0\0\0\xf0\x3f", 8), zero(8, '\0'), two("\0\0\0\0\0\0\0\x40", 8);
  WriteFile(tmp / "images.bin", LittleEndianBytes(1, 8) + LittleEndianBytes(9, 4) + one + zero + zero + zero +
                                     two + zero + one + LittleEndianBytes(3, 4) + std::string("a/b.png\0", 8) +
                                     LittleEndianBytes(1, 8) + one + two + std::string(8, '\xff'));
  WriteFile(tmp / "points3D.bin", LittleEndianBytes(1, 8) + LittleEndianBytes(77, 8) + one + two + zero +
                                       std::string("\x01\x02\x03", 3) + two + LittleEndianBytes(1, 8) +
                                       LittleEndianBytes(9, 4) + LittleEndianBytes(0, 4));
  const ColmapModel m = ReadColmapModel(tmp.path().string());
  EXPECT_EQ(m.cameras.at(3).model, "SIMPLE_PINHOLE");
  EXPECT_EQ(m.cameras.at(3).params, (std::vector<double>{10, 5, 4}));
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].image_id, 9u);
  EXPECT_EQ(m.images[0].name, "a/b.png");
  EXPECT_EQ(m.images[0].cam_from_world_translation, Eigen::Vector3d(2, 0, 1));
  ASSERT_EQ(m.images[0].points2D.size(), 1u);
  EXPECT_EQ(m.images[0].points2D[0].xy, Eigen::Vector2d(1, 2));
  EXPECT_EQ(m.images[0].points2D[0].point3D_id, UINT64_MAX);
  const ColmapPoint3D& p = m.points3D.at(77);
  EXPECT_EQ(p.xyz, Eigen::Vector3d(1, 2, 0));
  EXPECT_EQ(p.rgb, (std::array<uint8_t, 3>{1, 2, 3}));
  EXPECT_EQ(p.error, 2.0);
  ASSERT_EQ(p.track.size(), 1u);
  EXPECT_EQ(p.track[0].image_id, 9u);
}

TEST(ColmapModelTest, UtmTranslationsSurviveExactly) {
  const Eigen::Vector3d centre(390000.5, 5705000.25, 900);
  ColmapModel model;
  model.cameras[1] = ColmapCamera{1, "PINHOLE", 100, 100, {50, 50, 50, 50}};
  ColmapImage img;
  img.image_id = 1;
  img.camera_id = 1;
  img.name = "utm.jpg";
  img.cam_from_world_rotation = Eigen::Quaterniond(0, 1, 0, 0);  // nadir: 180 degrees about x
  img.cam_from_world_translation = -(img.cam_from_world_rotation * centre);
  model.images = {img};
  for (const bool binary : {true, false}) {
    TempDir tmp;
    binary ? WriteColmapModelBinary(model, tmp.path().string()) : WriteColmapModelText(model, tmp.path().string());
    const ColmapImage back = ReadColmapModel(tmp.path().string()).images.at(0);
    EXPECT_EQ(back.cam_from_world_translation, img.cam_from_world_translation) << (binary ? "binary" : "text");
    const Eigen::Vector3d back_centre = -(back.cam_from_world_rotation.conjugate() * back.cam_from_world_translation);
    EXPECT_EQ(back_centre, centre) << (binary ? "binary" : "text");
  }
}

TEST(ColmapModelTest, PrefersBinaryOverText) {
  TempDir tmp;
  WriteHandMadeText(tmp.path());
  ColmapModel other;
  other.cameras[9] = ColmapCamera{9, "PINHOLE", 1, 1, {1, 1, 0.5, 0.5}};
  WriteColmapModelBinary(other, tmp.path().string());
  const ColmapModel model = ReadColmapModel(tmp.path().string());
  EXPECT_EQ(model.cameras.count(9), 1u);
  EXPECT_TRUE(model.images.empty());
}

TEST(ColmapModelTest, NormalisesNonUnitQuaternions) {
  TempDir tmp;
  WriteFile(tmp / "cameras.txt", "1 PINHOLE 10 10 5 5 5 5\n");
  WriteFile(tmp / "images.txt", "1 2 0 0 2 0 0 0 1 a.png\n\n");
  WriteFile(tmp / "points3D.txt", "");
  const Eigen::Quaterniond q = ReadColmapModel(tmp.path().string()).images[0].cam_from_world_rotation;
  EXPECT_DOUBLE_EQ(q.w(), std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(q.z(), std::sqrt(0.5));
  WriteFile(tmp / "images.txt", "1 0 0 0 0 0 0 0 1 a.png\n\n");
  ExpectModelError(tmp.path(), {"images.txt", "line 1", "quaternion"});
}

TEST(ColmapModelTest, MissingFilesAreNamed) {
  TempDir tmp;
  ExpectModelError(tmp.path(), {"cameras.bin", "cameras.txt"});
  WriteHandMadeText(tmp.path());
  std::filesystem::remove(tmp / "points3D.txt");
  ExpectModelError(tmp.path(), {"points3D.bin", "missing"});
}

TEST(ColmapModelTest, TruncatedBinaryNamesTheRecord) {
  TempDir tmp;
  WriteColmapModelBinary(MakeModel(), tmp.path().string());
  const std::string images = ReadFile(tmp / "images.bin");
  // Cut inside the second image's name.
  const size_t cut = images.find("b.png") + 2;
  WriteFile(tmp / "images.bin", images.substr(0, cut));
  ExpectModelError(tmp.path(), {"images.bin", "truncated", "image record 2 of 2", "image_id 2"});
  WriteFile(tmp / "images.bin", images + "x");
  ExpectModelError(tmp.path(), {"images.bin", "trailing"});
  WriteFile(tmp / "images.bin", images);
  const std::string cameras = ReadFile(tmp / "cameras.bin");
  WriteFile(tmp / "cameras.bin", cameras.substr(0, cameras.size() - 3));
  ExpectModelError(tmp.path(), {"cameras.bin", "truncated", "camera record 12 of 12"});
  WriteFile(tmp / "cameras.bin", cameras.substr(0, 4));
  ExpectModelError(tmp.path(), {"cameras.bin", "truncated"});
  // A count header larger than the file can hold fails before allocating.
  WriteFile(tmp / "cameras.bin", LittleEndianBytes(1ull << 60, 8));
  ExpectModelError(tmp.path(), {"cameras.bin", "truncated"});
}

TEST(ColmapModelTest, UnknownCameraModels) {
  TempDir tmp;
  WriteFile(tmp / "cameras.bin", LittleEndianBytes(1, 8) + LittleEndianBytes(1, 4) + LittleEndianBytes(42, 4) +
                                      std::string(16 + 3 * 8, '\0'));
  WriteFile(tmp / "images.bin", LittleEndianBytes(0, 8));
  WriteFile(tmp / "points3D.bin", LittleEndianBytes(0, 8));
  ExpectModelError(tmp.path(), {"cameras.bin", "unknown camera model id 42", "camera record 1 of 1"});
  TempDir txt;
  WriteHandMadeText(txt.path());
  WriteFile(txt / "cameras.txt", "# comment\n1 PINHOLE 10 10 5 5 5 5\n2 FANCY 10 10 1 2 3\n");
  ExpectModelError(txt.path(), {"cameras.txt", "line 3", "unknown camera model \"FANCY\""});
}

TEST(ColmapModelTest, WrongParamCount) {
  TempDir tmp;
  WriteHandMadeText(tmp.path());
  WriteFile(tmp / "cameras.txt", "1 SIMPLE_PINHOLE 3072 2304 2559.81 1536\n2 PINHOLE 10 10 5 5 5 5\n");
  ExpectModelError(tmp.path(), {"cameras.txt", "line 1", "SIMPLE_PINHOLE takes 3 parameters, got 2"});
}

TEST(ColmapModelTest, ImageWithMissingCamera) {
  TempDir tmp;
  WriteHandMadeText(tmp.path());
  WriteFile(tmp / "cameras.txt", "2 PINHOLE 10 10 5 5 5 5\n");
  ExpectModelError(tmp.path(), {"images.txt", "P1180141.JPG", "camera_id 1"});
}

TEST(ColmapModelTest, MalformedTextLinesGiveLineNumbers) {
  TempDir tmp;
  WriteHandMadeText(tmp.path());
  std::string images = kImagesTxt;
  images.replace(images.find("-0.737434"), 9, "-0.7x7434");
  WriteFile(tmp / "images.txt", images);
  ExpectModelError(tmp.path(), {"images.txt", "line 5", "-0.7x7434"});
  images = kImagesTxt;
  images.replace(images.find(" -1\n"), 4, "\n");  // POINTS2D with 5 fields
  WriteFile(tmp / "images.txt", images);
  ExpectModelError(tmp.path(), {"images.txt", "line 6", "multiple of 3"});
  WriteFile(tmp / "images.txt", "1 1 0 0 0 0 0 0 1\n");  // no name
  ExpectModelError(tmp.path(), {"images.txt", "line 1"});
  WriteFile(tmp / "images.txt", kImagesTxt);
  WriteFile(tmp / "points3D.txt", "\n# c\n1 1 2 3 4 5 6 0.5 1\n");  // odd track
  ExpectModelError(tmp.path(), {"points3D.txt", "line 3"});
  WriteFile(tmp / "points3D.txt", "1 1 2 3 4 256 6 0.5\n");
  ExpectModelError(tmp.path(), {"points3D.txt", "line 1", "256"});
}

TEST(ColmapModelTest, DuplicatedIds) {
  TempDir tmp;
  WriteHandMadeText(tmp.path());
  WriteFile(tmp / "cameras.txt", std::string(kCamerasTxt) + "2 PINHOLE 10 10 5 5 5 5\n");
  ExpectModelError(tmp.path(), {"cameras.txt", "line 6", "duplicated camera_id 2"});
  WriteFile(tmp / "cameras.txt", kCamerasTxt);
  WriteFile(tmp / "images.txt", std::string(kImagesTxt) + "1 1 0 0 0 0 0 0 1 again.jpg\n\n");
  ExpectModelError(tmp.path(), {"images.txt", "duplicated image_id 1", "again.jpg"});
  WriteFile(tmp / "images.txt", kImagesTxt);
  WriteFile(tmp / "points3D.txt", std::string(kPoints3DTxt) + "58396 0 0 0 0 0 0 0\n");
  ExpectModelError(tmp.path(), {"points3D.txt", "line 5", "duplicated point3D_id 58396"});

  TempDir bin;
  ColmapModel model = MakeModel();
  model.points3D.clear();
  WriteColmapModelBinary(model, bin.path().string());
  const std::string images = ReadFile(bin / "images.bin");
  // Make the second image's id equal the first's (5).
  std::string dup = images;
  // First record: ... name "nadir/IMG 0001.JPG\0", u64 num_points2D = 2, 2 x 24 bytes; then image_id 2.
  const size_t second = images.find("0001.JPG") + 9 + 8 + 2 * 24;
  ASSERT_EQ(images.substr(second, 4), std::string("\x02\0\0\0", 4));
  dup[second] = '\x05';
  WriteFile(bin / "images.bin", dup);
  ExpectModelError(bin.path(), {"images.bin", "duplicated image_id 5"});
}

TEST(ColmapModelTest, CameraModelTable) {
  EXPECT_EQ(ColmapCameraModelId("SIMPLE_PINHOLE"), 0);
  EXPECT_EQ(ColmapCameraModelId("OPENCV"), 4);
  EXPECT_EQ(ColmapCameraModelId("FULL_OPENCV"), 6);
  EXPECT_EQ(ColmapCameraModelId("THIN_PRISM_FISHEYE"), 10);
  EXPECT_EQ(ColmapCameraModelId("nope"), -1);
  EXPECT_EQ(ColmapCameraModelName(7), "FOV");
  EXPECT_EQ(ColmapCameraModelName(-1), "");
  EXPECT_EQ(ColmapCameraModelNumParams("OPENCV_FISHEYE"), 8);
  EXPECT_EQ(ColmapCameraModelNumParams("FULL_OPENCV"), 12);
  EXPECT_EQ(ColmapCameraModelNumParams("RADIAL_FISHEYE"), 5);
}

}  // namespace
}  // namespace sacfuse
