#include "tools/sim/sgbm_depth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tools/sim/pair_merge.h"
#include "tools/sim/sgbm_pair.h"
#include "tools/sim/stereo_rectify.h"

namespace sacfuse::sim {
namespace {

// Linear-interpolated percentile (0..100) of sorted values.
double Percentile(const std::vector<double>& sorted, double percent) {
  const double pos = percent / 100.0 * static_cast<double>(sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (pos - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

struct DepthRange {
  double near_m = 0.0, far_m = 0.0;
  bool valid() const { return near_m > 0.0 && far_m > near_m; }
};

// The search range of a pair (see the header) from the reference view's sparse points in the rectified frame.
DepthRange SearchRange(const StereoView& ref, const SparsePoints& points, const Eigen::Matrix3d& rect_from_ref,
                       const SgbmDepthOptions& options) {
  std::vector<double> z;
  z.reserve(ref.point_ids.size());
  for (const uint64_t id : ref.point_ids) {
    const auto it = points.find(id);
    if (it == points.end()) continue;
    const double depth = (rect_from_ref * (ref.cam_from_world * it->second)).z();
    if (depth > 0.0) z.push_back(depth);
  }
  DepthRange range;
  if (z.size() < 3) return range;
  std::sort(z.begin(), z.end());
  const double low = Percentile(z, options.depth_percentile);
  const double high = Percentile(z, 100.0 - options.depth_percentile);
  range.near_m = std::min(low * (1.0 - options.depth_margin), options.near_fraction * Percentile(z, 50.0));
  range.far_m = high * (1.0 + options.depth_margin);
  return range;
}

}  // namespace

SgbmViewDepth ComputeSgbmDepth(uint32_t v, const std::vector<StereoView>& views, const SparsePoints& points,
                               const std::vector<uint32_t>& sources, const GreyImageLoader& grey,
                               const SgbmDepthOptions& options) {
  const StereoView& ref = views[v];
  SgbmViewDepth out;
  std::vector<DepthMap> pair_depths;
  cv::Mat ref_grey;
  for (const uint32_t s : sources) {
    const StereoView& src = views[s];
    const DepthRange range =
        SearchRange(ref, points, RectifyingRotation(ref.cam_from_world, src.cam_from_world), options);
    if (!range.valid()) continue;
    if (ref_grey.empty()) ref_grey = grey(v);
    const RectifiedPair pair = RectifyPair(ref.camera, ref.cam_from_world, src.camera, src.cam_from_world,
                                           range.near_m, range.far_m, options.max_disparities);
    PairDepthResult matched = MatchPair(ref_grey, ref.camera, grey(s), pair, options.match);
    out.sources.push_back(s);
    out.pair_valid_fraction.push_back(matched.valid_fraction);
    out.match_seconds += matched.match_seconds;
    pair_depths.push_back(std::move(matched.depth));
  }
  if (pair_depths.empty()) {
    out.depth = DepthMap(ref.camera.width, ref.camera.height, 1, 0.0f);
    return out;
  }
  out.depth = MergePairDepths(pair_depths, options.merge_tolerance, options.min_agree).depth;
  size_t valid = 0;
  for (const float d : out.depth.data) valid += IsValidDepth(d) ? 1 : 0;
  out.valid_fraction = static_cast<double>(valid) / static_cast<double>(out.depth.num_pixels());
  return out;
}

}  // namespace sacfuse::sim
