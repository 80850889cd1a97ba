#include "io/geo_mask_io.h"

#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/json_text.h"

namespace sacfuse {
namespace {
std::string SidecarPath(const std::string& png_path) {
  const auto dot = png_path.find_last_of('.');
  return (dot == std::string::npos ? png_path : png_path.substr(0, dot)) + ".json";
}
}  // namespace

void WriteGeoMask(const std::string& png_path, const GeoMask& mask, const std::string& crs) {
  if (mask.cells.size() != static_cast<size_t>(mask.width) * mask.height) {
    throw Error("WriteGeoMask: cells do not match width x height for " + png_path);
  }
  cv::Mat img(mask.height, mask.width, CV_8UC1);
  for (int r = 0; r < mask.height; ++r) {
    for (int c = 0; c < mask.width; ++c) img.at<uint8_t>(r, c) = mask.cells[static_cast<size_t>(r) * mask.width + c] ? 255 : 0;
  }
  std::vector<uint8_t> png;
  if (!cv::imencode(".png", img, png)) throw Error("WriteGeoMask: PNG encoding failed for " + png_path);
  WriteFileAtomically(png_path, std::string(png.begin(), png.end()));
  nlohmann::json j = {{"origin_x", mask.origin_x}, {"origin_y", mask.origin_y}, {"cell_size_m", mask.cell_size_m},
                      {"width", mask.width},       {"height", mask.height},     {"crs", crs}};
  WriteFileAtomically(SidecarPath(png_path), JsonText(j, 2) + "\n");
}

GeoMask ReadGeoMask(const std::string& png_path) {
  std::ifstream in = OpenInputStream(SidecarPath(png_path), "evaluation mask's JSON sidecar");
  CheckInputFile(png_path, "evaluation mask PNG");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw InputError(SidecarPath(png_path), std::string("malformed JSON: ") + e.what());
  }
  GeoMask mask;
  try {
    mask.origin_x = j.at("origin_x").get<double>();
    mask.origin_y = j.at("origin_y").get<double>();
    mask.cell_size_m = j.at("cell_size_m").get<double>();
    mask.width = j.at("width").get<int>();
    mask.height = j.at("height").get<int>();
  } catch (const std::exception& e) {
    throw InputError(SidecarPath(png_path), std::string("missing or wrong field: ") + e.what());
  }
  cv::Mat img = cv::imread(png_path, cv::IMREAD_GRAYSCALE);
  if (img.empty()) throw InputError(png_path, "cannot read the mask PNG");
  if (img.cols != mask.width || img.rows != mask.height) {
    throw InputError(png_path, "mask size " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                                   " differs from its sidecar's " + std::to_string(mask.width) + "x" +
                                   std::to_string(mask.height));
  }
  mask.cells.resize(static_cast<size_t>(mask.width) * mask.height);
  for (int r = 0; r < mask.height; ++r) {
    for (int c = 0; c < mask.width; ++c) mask.cells[static_cast<size_t>(r) * mask.width + c] = img.at<uint8_t>(r, c) > 127;
  }
  return mask;
}

}  // namespace sacfuse
