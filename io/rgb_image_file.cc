#include "io/rgb_image_file.h"

#include <cerrno>
#include <fstream>
#include <iterator>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/image_completeness.h"
#include "io/input_file.h"
#include "io/input_warnings.h"

namespace sacfuse {

RgbImage ReadRgbImageFile(const std::string& path, const std::string& who, int expected_width, int expected_height) {
  const std::string for_who = " (" + who + ")";
  const std::string what = "image file" + for_who;
  std::ifstream in = OpenInputStream(path, what);
  errno = 0;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) ThrowInputOsError(path, what, errno != 0 ? errno : EIO);
  if (bytes.size() > static_cast<size_t>(std::numeric_limits<int>::max())) {
    throw InputError(path, "image file larger than 2 GiB" + for_who);
  }
  if (const std::string problem = IncompleteImageProblem(bytes); !problem.empty()) {
    WarnAboutInput(path, problem + for_who);
  }
  cv::Mat bgr;
  try {
    const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
    bgr = cv::imdecode(encoded, cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION);
  } catch (const cv::Exception& e) {
    throw InputError(path, std::string("cannot decode image: ") + e.what() + for_who);
  }
  if (bgr.empty()) throw InputError(path, "cannot decode image (unsupported or corrupt)" + for_who);
  if (expected_width > 0 && (bgr.cols != expected_width || bgr.rows != expected_height)) {
    throw InputError(path, "image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
                               " but its camera is " + std::to_string(expected_width) + "x" +
                               std::to_string(expected_height) + for_who);
  }
  // OpenCV's BGR to RGB; every value is written here, so the raster is not zero-filled first.
  RgbImage rgb = RgbImage::Uninitialized(bgr.cols, bgr.rows, 3);
  for (int row = 0; row < bgr.rows; ++row) {
    const uint8_t* src = bgr.ptr<uint8_t>(row);
    uint8_t* dst = &rgb.at(row, 0, 0);
    for (int col = 0; col < bgr.cols; ++col) {
      dst[3 * col + 0] = src[3 * col + 2];
      dst[3 * col + 1] = src[3 * col + 1];
      dst[3 * col + 2] = src[3 * col + 0];
    }
  }
  return rgb;
}

void WriteRgbImagePng(const std::string& path, const RgbImage& image) {
  if (image.empty() || (image.channels != 3 && image.channels != 1)) {
    throw Error(path + ": cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  }
  cv::Mat bgr(image.height, image.width, image.channels == 3 ? CV_8UC3 : CV_8UC1);
  for (int row = 0; row < image.height; ++row) {
    uint8_t* dst = bgr.ptr<uint8_t>(row);
    const uint8_t* src = &image.at(row, 0, 0);
    for (int col = 0; col < image.width; ++col) {
      if (image.channels == 1) {
        dst[col] = src[col];
        continue;
      }
      dst[3 * col + 0] = src[3 * col + 2];
      dst[3 * col + 1] = src[3 * col + 1];
      dst[3 * col + 2] = src[3 * col + 0];
    }
  }
  std::vector<uint8_t> png;
  if (!cv::imencode(".png", bgr, png)) throw Error(path + ": PNG encoding failed");
  WriteFileAtomically(path, std::string(png.begin(), png.end()));
}

}  // namespace sacfuse
