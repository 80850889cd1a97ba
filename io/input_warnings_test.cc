// Input problems that do not stop a run become warnings naming the file in the log (sacfuse.log is attached to
// spdlog's default logger): truncated JPEG/PNG images, libtiff warnings, depth maps without a valid pixel
// (issue 14: libjpeg's "Premature end of JPEG file" reached only stderr, unattributed; an all-invalid depth map
// got no message).
#include "io/input_warnings.h"

#include <tiffio.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "io/colmap_array.h"
#include "io/colmap_model.h"
#include "io/colmap_workspace.h"
#include "io/depth_block.h"
#include "io/image_completeness.h"
#include "io/rgb_image_file.h"
#include "io/tiff_depth.h"
#include "tests/support/log_capture.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::LogCapture;
using sacfuse::testing::TempDir;

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

size_t Count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t p = text.find(part); p != std::string::npos; p = text.find(part, p + 1)) ++n;
  return n;
}

std::string Encoded(const char* ext) {
  cv::Mat img(48, 64, CV_8UC3);
  cv::randu(img, 0, 255);
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(ext, img, bytes));
  return std::string(bytes.begin(), bytes.end());
}

void Write(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// Reads an image, ignoring whether the decoder manages (a truncated file may decode partly or not at all).
void TryRead(const fs::path& path) {
  try {
    ReadRgbImageFile(path.string(), "image \"x\"");
  } catch (const InputError&) {
  }
}

TEST(InputWarningsTest, TruncatedJpegIsAWarningNamingTheFile) {
  TempDir dir;
  const std::string jpeg = Encoded(".jpg");
  Write(dir / "whole.jpg", jpeg);
  Write(dir / "cut.jpg", jpeg.substr(0, jpeg.size() * 2 / 3));
  LogCapture log;
  EXPECT_NO_THROW(ReadRgbImageFile((dir / "whole.jpg").string(), "image \"whole.jpg\""));
  EXPECT_EQ(log.text(), "");
  TryRead(dir / "cut.jpg");
  EXPECT_TRUE(Has(log.text(), "[warning] " + (dir / "cut.jpg").string() +
                                  ": JPEG file without an end of image marker (EOI) after its last scan: truncated"))
      << log.text();
}

TEST(InputWarningsTest, PngWithoutIendIsAWarningNamingTheFile) {
  TempDir dir;
  const std::string png = Encoded(".png");
  Write(dir / "cut.png", png.substr(0, png.size() - 12));
  LogCapture log;
  TryRead(dir / "cut.png");
  EXPECT_TRUE(Has(log.text(), (dir / "cut.png").string() + ": PNG file without its IEND chunk: truncated"))
      << log.text();
}

TEST(InputWarningsTest, CompletenessRules) {
  const std::string jpeg = Encoded(".jpg");
  EXPECT_EQ(IncompleteImageProblem(jpeg), "");
  EXPECT_EQ(IncompleteImageProblem(jpeg + "trailing bytes"), "");
  EXPECT_NE(IncompleteImageProblem(jpeg.substr(0, jpeg.size() - 2)), "");
  EXPECT_NE(IncompleteImageProblem(jpeg.substr(0, 200)), "");
  const std::string png = Encoded(".png");
  EXPECT_EQ(IncompleteImageProblem(png), "");
  EXPECT_NE(IncompleteImageProblem(png.substr(0, png.size() - 1)), "");
  EXPECT_EQ(IncompleteImageProblem("BM not a jpeg or png"), "");
}

TEST(InputWarningsTest, LibtiffWarningsOfAReadableRasterNameTheFileOnce) {
  TempDir dir;
  const fs::path path = dir / "private_tag.tif";
  TIFF* tif = TIFFOpen(path.c_str(), "w");
  ASSERT_NE(tif, nullptr);
  static const TIFFFieldInfo kPrivate[] = {{65000, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, const_cast<char*>("P")}};
  TIFFMergeFieldInfo(tif, kPrivate, 1);
  TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, 8u);
  TIFFSetField(tif, TIFFTAG_IMAGELENGTH, 4u);
  TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, 32);
  TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, 1);
  TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP);
  TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
  TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, 4u);
  TIFFSetField(tif, 65000, "private");
  std::vector<float> data(32, 5.0f);
  ASSERT_GE(TIFFWriteEncodedStrip(tif, 0, data.data(), 128), 0);
  TIFFClose(tif);
  LogCapture log;
  EXPECT_EQ(ReadTiffDepth(path.string()).at(0, 0), 5.0f);
  EXPECT_EQ(ReadTiffDepth(path.string()).at(3, 7), 5.0f);
  EXPECT_EQ(Count(log.text(), "[warning] " + path.string() + ": libtiff warnings: "), 1u) << log.text();
  EXPECT_TRUE(Has(log.text(), "65000")) << log.text();
}

TEST(InputWarningsTest, ADepthMapWithoutAValidPixelIsAWarningNamingTheViewAndFile) {
  TempDir dir;
  ColmapModel m;
  m.cameras[1] = {1, "PINHOLE", 64, 48, {50.0, 50.0, 32.0, 24.0}};
  ColmapImage img;
  img.image_id = 1;
  img.camera_id = 1;
  img.name = "empty.jpg";
  img.cam_from_world_rotation = Eigen::Quaterniond(0, 1, 0, 0);
  img.cam_from_world_translation = {0, 0, 100};
  m.images.push_back(img);
  img.image_id = 2;
  img.name = "full.jpg";
  m.images.push_back(img);
  fs::create_directories(dir / "sparse");
  WriteColmapModelText(m, (dir / "sparse").string());
  Raster<float> nothing(64, 48, 1, 0.0f);
  nothing.at(3, 3) = -2.0f;
  nothing.at(4, 4) = std::numeric_limits<float>::quiet_NaN();
  WriteColmapArray((dir / "stereo/depth_maps/empty.jpg.geometric.bin").string(), nothing);
  Raster<float> one(64, 48, 1, 0.0f);
  one.at(5, 5) = 80.0f;
  WriteColmapArray((dir / "stereo/depth_maps/full.jpg.geometric.bin").string(), one);
  const ColmapWorkspace ws(dir.path().string(), ColmapDepthType::kGeometric);
  LogCapture log;
  ws.ReadDepthMap(ws.views()[0]);
  ws.ReadDepthMap(ws.views()[0]);
  ws.ReadDepthMap(ws.views()[1]);
  const std::string expected = "[warning] " + ws.DepthMapPath(ws.views()[0]) +
                               ": depth map of view 0 (\"empty.jpg\") has no valid depth pixel";
  EXPECT_EQ(Count(log.text(), expected), 1u) << log.text();
  EXPECT_FALSE(Has(log.text(), "full.jpg")) << log.text();
}

}  // namespace
}  // namespace sacfuse
