#include "tools/sim/sim_workspace.h"

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "io/atomic_file.h"

namespace sacfuse::sim {

namespace fs = std::filesystem;

void CreateParentDirs(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw Error(parent.string() + ": cannot create folder: " + ec.message());
}

void WriteJpeg(const std::string& path, const RgbImage& image, int quality) {
  if (image.channels != 3 || image.empty()) throw Error(path + ": WriteJpeg needs a non-empty RGB image");
  cv::Mat bgr(image.height, image.width, CV_8UC3);
  for (int row = 0; row < image.height; ++row) {
    auto* out = bgr.ptr<uint8_t>(row);
    const uint8_t* in = &image.data[static_cast<size_t>(row) * image.width * 3];
    for (int col = 0; col < image.width; ++col) {
      out[3 * col + 0] = in[3 * col + 2];
      out[3 * col + 1] = in[3 * col + 1];
      out[3 * col + 2] = in[3 * col + 0];
    }
  }
  std::vector<uint8_t> buffer;
  if (!cv::imencode(".jpg", bgr, buffer, {cv::IMWRITE_JPEG_QUALITY, quality})) {
    throw Error(path + ": JPEG encoding failed");
  }
  CreateParentDirs(path);
  WriteFileAtomically(path, std::string(buffer.begin(), buffer.end()));
}

void CreateRelativeSymlink(const std::string& target_path, const std::string& link_path) {
  CreateParentDirs(link_path);
  const fs::path link_dir = fs::absolute(fs::path(link_path)).lexically_normal().parent_path();
  const fs::path relative = fs::absolute(target_path).lexically_normal().lexically_relative(link_dir);
  std::error_code ec;
  fs::remove(link_path, ec);
  fs::create_symlink(relative, link_path, ec);
  if (ec) throw Error(link_path + ": cannot create symlink to " + relative.string() + ": " + ec.message());
}

}  // namespace sacfuse::sim
