#include "report/report_png.h"

#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "io/atomic_file.h"

namespace sacfuse {

std::string EncodePng(const RgbImage& image) {
  if (image.channels != 3 || image.empty()) throw Error("EncodePng: needs a non-empty 3-channel image");
  const cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.data.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<uchar> bytes;
  if (!cv::imencode(".png", bgr, bytes, {cv::IMWRITE_PNG_COMPRESSION, 6})) throw Error("PNG encoding failed");
  return std::string(bytes.begin(), bytes.end());
}

void WritePng(const std::string& path, const RgbImage& image) { WriteFileAtomically(path, EncodePng(image)); }

}  // namespace sacfuse
