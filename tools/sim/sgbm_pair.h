#pragma once
// Depth of one reference view from one stereo pair with OpenCV's semi-global matcher (cv::StereoSGBM, 3-way):
// both grey images are warped onto the pair's rectified canvases (tools/sim/stereo_rectify.h), matched, and the
// disparities turned into depth along the reference view's rays on its own pixel grid (nearest canvas pixel).
// What a real CPU pipeline does without COLMAP's CUDA patch_match_stereo, so the depth carries a matcher's errors:
// holes in shadows and on weak texture, streaks, fattened edges, wrong matches at walls and canopies.
//
// Kept: disparities strictly inside the search range (a match at either end is a clipped one), on the warped
// reference image and onto the warped source image (both eroded by erode_px, the matcher's unreliable rim), after
// SGBM's own left-right check (disp12MaxDiff), uniqueness test and speckle filter.
#include <opencv2/core.hpp>

#include "core/camera.h"
#include "core/raster.h"
#include "tools/sim/sgbm_options.h"
#include "tools/sim/stereo_rectify.h"

namespace sacfuse::sim {

struct PairDepthResult {
  DepthMap depth;              // on the reference grid (ref_camera's size), z in the reference camera, 0 = invalid
  double valid_fraction = 0.0;
  double match_seconds = 0.0;  // cv::StereoSGBM::compute alone
};

// `ref_grey`, `src_grey`: 8-bit grey images (CV_8UC1) at the resolutions of the cameras the pair was rectified
// with. OpenCV's own thread setting applies (cv::setNumThreads).
PairDepthResult MatchPair(const cv::Mat& ref_grey, const PinholeCamera& ref_camera, const cv::Mat& src_grey,
                          const RectifiedPair& pair, const SgbmMatchOptions& options);

}  // namespace sacfuse::sim
