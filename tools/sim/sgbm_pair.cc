#include "tools/sim/sgbm_pair.h"

#include <chrono>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>

namespace sacfuse::sim {
namespace {

cv::Matx33d ToCv(const Eigen::Matrix3d& m) {
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out(r, c) = m(r, c);
  }
  return out;
}

// Where the warped image has content: 255 on canvas pixels whose source pixel lies on `image`, eroded by erode_px.
cv::Mat WarpedValidity(const cv::Mat& image, const cv::Matx33d& canvas_to_image, const cv::Size& canvas,
                       int erode_px) {
  const cv::Mat ones(image.size(), CV_8UC1, cv::Scalar(255));
  cv::Mat valid;
  cv::warpPerspective(ones, valid, canvas_to_image, canvas, cv::INTER_NEAREST | cv::WARP_INVERSE_MAP,
                      cv::BORDER_CONSTANT, cv::Scalar(0));
  if (erode_px > 0) {
    cv::erode(valid, valid, cv::Mat::ones(2 * erode_px + 1, 2 * erode_px + 1, CV_8UC1), cv::Point(-1, -1), 1,
              cv::BORDER_CONSTANT, cv::Scalar(0));
  }
  return valid;
}

}  // namespace

PairDepthResult MatchPair(const cv::Mat& ref_grey, const PinholeCamera& ref_camera, const cv::Mat& src_grey,
                          const RectifiedPair& pair, const SgbmMatchOptions& options) {
  const cv::Size canvas(pair.width, pair.height);
  const cv::Matx33d left_to_ref = ToCv(pair.left_to_ref), right_to_src = ToCv(pair.right_to_src);
  cv::Mat left, right;
  cv::warpPerspective(ref_grey, left, left_to_ref, canvas, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                      cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::warpPerspective(src_grey, right, right_to_src, canvas, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                      cv::BORDER_CONSTANT, cv::Scalar(0));
  const cv::Mat left_valid = WarpedValidity(ref_grey, left_to_ref, canvas, options.erode_px);
  const cv::Mat right_valid = WarpedValidity(src_grey, right_to_src, canvas, options.erode_px);

  const int b = options.block_size;
  cv::Ptr<cv::StereoSGBM> sgbm = cv::StereoSGBM::create(
      0, pair.num_disparities, b, 8 * b * b, options.p2_multiplier * b * b, options.left_right_max_diff, 63,
      options.uniqueness_percent, options.speckle_window_px, options.speckle_range, cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat disparity16;
  const auto start = std::chrono::steady_clock::now();
  sgbm->compute(left, right, disparity16);
  PairDepthResult result;
  result.match_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Rectified depth per canvas pixel (0 = no match kept).
  cv::Mat rect_depth(canvas, CV_32FC1, cv::Scalar(0));
  for (int r = 0; r < pair.height; ++r) {
    const int16_t* d16 = disparity16.ptr<int16_t>(r);
    const uint8_t* lv = left_valid.ptr<uint8_t>(r);
    const uint8_t* rv = right_valid.ptr<uint8_t>(r);
    float* z = rect_depth.ptr<float>(r);
    for (int c = 0; c < pair.width; ++c) {
      const double d = d16[c] / 16.0;
      if (!(d > 1.0) || !(d < pair.num_disparities - 2) || lv[c] == 0) continue;
      const double right_col = c - d;
      const int rc = static_cast<int>(std::lround(right_col));
      if (right_col < 0 || rc >= pair.width || rv[rc] == 0) continue;
      z[c] = static_cast<float>(pair.RectifiedDepth(d));
    }
  }

  // Back onto the reference grid: each reference pixel's ray in the rectified frame, nearest canvas pixel.
  const Eigen::Matrix3d ref_k_inv = IndexCameraMatrix(ref_camera).inverse();
  result.depth = DepthMap(ref_camera.width, ref_camera.height, 1, 0.0f);
  size_t valid = 0;
  for (int r = 0; r < ref_camera.height; ++r) {
    for (int c = 0; c < ref_camera.width; ++c) {
      const Eigen::Vector3d q = pair.rect_from_ref * (ref_k_inv * Eigen::Vector3d(c, r, 1.0));
      if (!(q.z() > 0.0)) continue;
      const long u = std::lround(pair.focal_px * q.x() / q.z() + pair.left_cx);
      const long v = std::lround(pair.focal_px * q.y() / q.z() + pair.cy);
      if (u < 0 || v < 0 || u >= pair.width || v >= pair.height) continue;
      const float z_rect = rect_depth.at<float>(static_cast<int>(v), static_cast<int>(u));
      if (!(z_rect > 0.0f)) continue;
      // The ray q has unit z in the reference frame, so its rectified depth is z_ref * q.z.
      result.depth.at(r, c) = static_cast<float>(z_rect / q.z());
      ++valid;
    }
  }
  result.valid_fraction = static_cast<double>(valid) / static_cast<double>(result.depth.num_pixels());
  return result;
}

}  // namespace sacfuse::sim
