#include "core/point_verdicts.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/method_views.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

constexpr int kPatchRows = 16;  // pixels judged together (see JudgePoints)
constexpr int kPatchCols = 32;

// `hits[k]`: the point looked up in neighbors[k].
bool PassesOutlierTest(const std::vector<SacView>& views, uint32_t v, double d, const std::vector<uint32_t>& neighbors,
                       const DepthLookup* hits, const std::vector<double>& noise_factor, const SacOptions& options) {
  if (options.min_consistent_views <= 1) return true;
  // Views that can observe the point: they agree, or they see through it (free space). Views where it is occluded
  // (their surface lies in front) cannot judge it and are not counted.
  int agree = 1, observers = 0;
  double expected_agree = 0.0;  // with estimated noise: sum of P(|difference| <= tolerance) over the observers
  const bool noise_aware = !noise_factor.empty() && options.outlier_expected_factor > 0;
  const double sigma_own = noise_aware ? DepthSigmaM(views, noise_factor, v, d) : 0.0;
  for (size_t k = 0; k < neighbors.size(); ++k) {
    const uint32_t b = neighbors[k];
    const DepthLookup& hit = hits[k];
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

// Whether at least options.free_space_min_views of `judges` see through X (see the header). `neighbor_slot[b]`: the
// index of view b in the neighbour list whose lookups `neighbor_hits` holds, or -1 (those are not looked up again).
bool InFreeSpace(const std::vector<SacView>& views, uint32_t v, const Eigen::Vector3d& point, double d,
                 const std::vector<uint32_t>& judges, const std::vector<int>& neighbor_slot,
                 const DepthLookup* neighbor_hits, const std::vector<double>& noise_factor, const SacOptions& options) {
  const double sigma_own = noise_factor.empty() ? 0.0 : DepthSigmaM(views, noise_factor, v, d);
  int count = 0;
  for (const uint32_t b : judges) {
    if (b == v) continue;
    const DepthLookup hit = neighbor_slot[b] >= 0 ? neighbor_hits[neighbor_slot[b]] : LookupDepth(views[b], point);
    if (!hit.inside || !IsValidDepth(hit.stored_depth_m)) continue;
    const double sigma_pair =
        noise_factor.empty() ? 0.0 : PairSigmaM(sigma_own, DepthSigmaM(views, noise_factor, b, hit.z_m));
    const double margin = std::max(DepthToleranceM(views[b], hit.z_m, options), options.free_space_sigmas * sigma_pair);
    if (hit.stored_depth_m - hit.z_m > margin && ++count >= options.free_space_min_views) return true;
  }
  return false;
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
    // Each point is looked up once in each neighbour; the free-space test reuses those lookups.
    const std::vector<uint32_t>& near = neighbors[v];
    std::vector<int> neighbor_slot(views.size(), -1);
    for (size_t k = 0; k < near.size(); ++k) neighbor_slot[near[k]] = static_cast<int>(k);
    // Cache-friendly order: the points of a patch of kPatchRows x kPatchCols pixels land in compact patches of the
    // other views' depth maps, which stay in cache while the patch is judged. (Row by row, an oblique neighbour
    // whose rows run across this view's rows was read one cache line per pixel: the reads of LookupDepth's depth
    // value were ~78 % of its time.) Each verdict depends on its pixel only, so the order changes nothing else.
    const int patch_rows = (depth.height + kPatchRows - 1) / kPatchRows;
    const int patch_cols = (depth.width + kPatchCols - 1) / kPatchCols;
    tbb::parallel_for(0, patch_rows * patch_cols, [&](int patch) {
      std::vector<DepthLookup> hits(near.size());
      const int row0 = (patch / patch_cols) * kPatchRows, col0 = (patch % patch_cols) * kPatchCols;
      const int row_end = std::min(depth.height, row0 + kPatchRows), col_end = std::min(depth.width, col0 + kPatchCols);
      for (int row = row0; row < row_end; ++row) {
        for (int col = col0; col < col_end; ++col) {
          const float d = depth.at(row, col);
          if (!IsValidDepth(d)) continue;
          const Eigen::Vector3d point = PixelPoint(view, row, col, d);
          for (size_t k = 0; k < near.size(); ++k) hits[k] = LookupDepth(views[near[k]], point);
          PointVerdict verdict = PointVerdict::kPasses;
          if (!PassesOutlierTest(views, v, d, near, hits.data(), noise_factor, options)) {
            verdict = PointVerdict::kOutlier;
          } else if (options.free_space_min_views > 0 &&
                     InFreeSpace(views, v, point, d, judges[v], neighbor_slot, hits.data(), noise_factor, options)) {
            verdict = PointVerdict::kFreeSpace;
          }
          verdicts[static_cast<size_t>(row) * depth.width + col] = verdict;
        }
      }
    });
  }
  return out;
}

}  // namespace sacfuse
