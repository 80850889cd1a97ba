#include "core/point_verdicts.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/method_views.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

bool PassesOutlierTest(const std::vector<SacView>& views, uint32_t v, const Eigen::Vector3d& point, double d,
                       const std::vector<uint32_t>& neighbors, const std::vector<double>& noise_factor,
                       const SacOptions& options) {
  if (options.min_consistent_views <= 1) return true;
  // Views that can observe the point: they agree, or they see through it (free space). Views where it is occluded
  // (their surface lies in front) cannot judge it and are not counted.
  int agree = 1, observers = 0;
  double expected_agree = 0.0;  // with estimated noise: sum of P(|difference| <= tolerance) over the observers
  const bool noise_aware = !noise_factor.empty() && options.outlier_expected_factor > 0;
  const double sigma_own = noise_aware ? DepthSigmaM(views, noise_factor, v, d) : 0.0;
  for (const uint32_t b : neighbors) {
    const DepthLookup hit = LookupDepth(views[b], point);
    if (!hit.inside || !IsValidDepth(hit.stored_depth_m)) continue;
    const double tolerance = DepthToleranceM(views[b], hit.z_m, options);
    bool observes = false;
    if (std::abs(hit.stored_depth_m - hit.z_m) <= tolerance) {
      ++agree;
      observes = true;
    } else if (hit.stored_depth_m > hit.z_m + tolerance) {
      observes = true;
    }
    if (!observes) continue;
    ++observers;
    if (noise_aware) {
      const double sigma_b = DepthSigmaM(views, noise_factor, b, hit.z_m);
      expected_agree += std::erf(tolerance / (PairSigmaM(sigma_own, sigma_b) * std::sqrt(2.0)));
    }
  }
  int required = std::min(options.min_consistent_views, std::max(2, 1 + observers));
  if (noise_aware) {
    // Noisy depth maps rarely agree within the strict tolerance: ask no more than the noise lets agree.
    required = std::min(
        required, std::max(2, 1 + static_cast<int>(std::lround(options.outlier_expected_factor * expected_agree))));
  }
  return agree >= required;
}

// Views among `judges` whose depth at X's projection lies beyond X (see the header).
int SeeThroughViews(const std::vector<SacView>& views, uint32_t v, const Eigen::Vector3d& point, double d,
                    const std::vector<uint32_t>& judges, const std::vector<double>& noise_factor,
                    const SacOptions& options) {
  const double sigma_own = noise_factor.empty() ? 0.0 : DepthSigmaM(views, noise_factor, v, d);
  int count = 0;
  for (const uint32_t b : judges) {
    if (b == v) continue;
    const DepthLookup hit = LookupDepth(views[b], point);
    if (!hit.inside || !IsValidDepth(hit.stored_depth_m)) continue;
    const double sigma_pair =
        noise_factor.empty() ? 0.0 : PairSigmaM(sigma_own, DepthSigmaM(views, noise_factor, b, hit.z_m));
    const double margin = std::max(DepthToleranceM(views[b], hit.z_m, options), options.free_space_sigmas * sigma_pair);
    if (hit.stored_depth_m - hit.z_m > margin) ++count;
  }
  return count;
}

}  // namespace

PointVerdicts JudgePoints(const std::vector<SacView>& views, const std::vector<std::vector<uint32_t>>& neighbors,
                          const std::vector<std::vector<uint32_t>>& judges, const std::vector<double>& noise_factor,
                          const SacOptions& options) {
  PointVerdicts out;
  out.per_view.resize(views.size());
  for (uint32_t v = 0; v < views.size(); ++v) {
    const SacView& view = views[v];
    const DepthMap& depth = *view.depth;
    auto& verdicts = out.per_view[v];
    verdicts.assign(static_cast<size_t>(depth.width) * depth.height, PointVerdict::kInvalid);
    tbb::parallel_for(0, depth.height, [&](int row) {
      for (int col = 0; col < depth.width; ++col) {
        const float d = depth.at(row, col);
        if (!IsValidDepth(d)) continue;
        const Eigen::Vector3d point = PixelPoint(view, row, col, d);
        PointVerdict verdict = PointVerdict::kPasses;
        if (!PassesOutlierTest(views, v, point, d, neighbors[v], noise_factor, options)) {
          verdict = PointVerdict::kOutlier;
        } else if (options.free_space_min_views > 0 &&
                   SeeThroughViews(views, v, point, d, judges[v], noise_factor, options) >=
                       options.free_space_min_views) {
          verdict = PointVerdict::kFreeSpace;
        }
        verdicts[static_cast<size_t>(row) * depth.width + col] = verdict;
      }
    });
  }
  return out;
}

}  // namespace sacfuse
