#pragma once
// Depth maps made by a real matcher from the images of an oriented block (`sacfuse simulate --depth sgbm`): per
// view, stereo pairs with its source views (tools/sim/stereo_sources.h), each rectified under the WRITTEN poses
// (tools/sim/stereo_rectify.h) and matched by OpenCV's StereoSGBM (tools/sim/sgbm_pair.h), the pair depths merged
// (tools/sim/pair_merge.h). So the depth carries what real matching does to it (holes in shadows and on weak
// texture, streaks and fattening at edges, wrong matches at walls and canopies) and, like a real pipeline's, the
// block's pose errors (epipolar misalignment, baseline and scale errors), while the truth stays exact. The same
// route as the independent benchmark's make_block.py --depth sgbm (../shared/aerial-bench), written apart.
//
// Depth search range of a pair: the depths (in its rectified frame) of the sparse points the reference view
// observes, between the depth_percentile and 100 - depth_percentile percentiles, widened by depth_margin on both
// sides and reaching at least near_fraction of their median (tall objects, canopies and roofs, hold few sparse
// points), the search width capped at max_disparities.
#include <cstdint>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "core/raster.h"
#include "tools/sim/sgbm_options.h"
#include "tools/sim/stereo_sources.h"

namespace sacfuse::sim {

// A view's grey image (CV_8UC1) at its StereoView camera's resolution.
using GreyImageLoader = std::function<cv::Mat(uint32_t view)>;

struct SgbmViewDepth {
  DepthMap depth;                          // at views[v].camera's size, 0 = invalid
  std::vector<uint32_t> sources;
  std::vector<double> pair_valid_fraction;  // per source
  double valid_fraction = 0.0;
  double match_seconds = 0.0;              // StereoSGBM alone, all pairs
};

// The depth map of views[v] from its `sources`. A view without sources, or without sparse points to set a range,
// gets an all-invalid map.
SgbmViewDepth ComputeSgbmDepth(uint32_t v, const std::vector<StereoView>& views, const SparsePoints& points,
                               const std::vector<uint32_t>& sources, const GreyImageLoader& grey,
                               const SgbmDepthOptions& options);

}  // namespace sacfuse::sim
