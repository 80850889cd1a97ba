#include "core/point_verdicts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <tbb/parallel_for.h>

#include "core/depth_edge.h"
#include "core/method_views.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

constexpr size_t kMaxJudgingViews = 64;  // SacOptions.max_neighbor_views is at most 64

// Whether view b, whose depth map has no depth where X projects (`hit`), failed to match X's surface rather than
// being occluded there: no valid depth within kDepthEdgeReachPx pixels lies in front of X by more than `tolerance`
// (an occluder's invalid band behind its edge is that wide at most; core/depth_edge.h).
bool UnmatchedAt(const SacView& b, const DepthLookup& hit, double tolerance) {
  const double near_m = hit.z_m - tolerance;
  return !AnyDepthInWindow(*b.depth, hit.row, hit.col, kDepthEdgeReachPx,
                           [&](float q) { return IsValidDepth(q) && q < near_m; });
}

// Whether pixel (row, col) of `view` lies within options.weak_support_rim_px of a hole of its own depth map (weak
// support on): the rim of what the matcher matched. Pixels off the raster are no hole (the image border is not a rim).
bool OnMatchedRim(const SacView& view, int row, int col, const SacOptions& options) {
  return options.weak_support_min_views > 0 && options.weak_support_rim_px > 0 &&
         AnyDepthInWindow(*view.depth, row, col, options.weak_support_rim_px, [](float q) { return !IsValidDepth(q); });
}

// `hits[k]`: the point looked up in neighbors[k]. `on_rim`: OnMatchedRim of the point's pixel.
bool PassesOutlierTest(const std::vector<SacView>& views, uint32_t v, double d, const std::vector<uint32_t>& neighbors,
                       const DepthLookup* hits, const std::vector<double>& noise_factor, const SacOptions& options,
                       bool on_rim) {
  if (options.min_consistent_views <= 1) return true;
  // Views that can observe the point: they agree, or they see through it (free space). Views where it is occluded
  // (their surface lies in front) cannot judge it and are not counted. Unmatched views could observe it but have no
  // depth there (weak support).
  int agree = 1, observers = 0, unmatched = 0;
  const bool weak_support = options.weak_support_min_views > 0;
  double expected_agree = 0.0;  // with estimated noise: sum of P(|difference| <= tolerance) over the observers
  const bool noise_aware = !noise_factor.empty() && options.outlier_expected_factor > 0;
  const double sigma_own = noise_aware ? DepthSigmaM(views, noise_factor, v, d) : 0.0;
  for (size_t k = 0; k < neighbors.size(); ++k) {
    const uint32_t b = neighbors[k];
    const DepthLookup& hit = hits[k];
    if (!hit.inside) continue;
    const bool valid = IsValidDepth(hit.stored_depth_m);
    if (!valid && !weak_support) continue;
    const double tolerance = DepthToleranceM(views[b], hit.z_m, options);
    if (!valid) {
      if (!UnmatchedAt(views[b], hit, tolerance)) continue;
      ++unmatched;
    } else {
      bool observes = false;
      if (std::abs(hit.stored_depth_m - hit.z_m) <= tolerance) {
        ++agree;
        observes = true;
      } else if (hit.stored_depth_m > hit.z_m + tolerance) {
        observes = true;
      }
      if (!observes) continue;
      ++observers;
    }
    if (noise_aware) {
      const double sigma_b = DepthSigmaM(views, noise_factor, b, hit.z_m);
      expected_agree += std::erf(tolerance / (PairSigmaM(sigma_own, sigma_b) * std::sqrt(2.0)));
    }
  }
  int required = std::min(options.min_consistent_views, std::max(2, 1 + observers));
  if (unmatched > 0) {
    required = std::max(required, std::min({options.min_consistent_views, options.weak_support_min_views,
                                            1 + observers + unmatched}));
  }
  if (noise_aware) {
    // Noisy depth maps rarely agree within the strict tolerance: ask no more than the noise lets agree.
    required = std::min(
        required, std::max(2, 1 + static_cast<int>(std::lround(options.outlier_expected_factor * expected_agree))));
  }
  // On the rim of its own map's matched region a point needs weak_support_min_views maps however few views observe it
  // (and whatever the noise lets agree): there the matcher's single-pair depths stray most (docs/design.md).
  if (on_rim) required = std::max(required, std::min(options.min_consistent_views, options.weak_support_min_views));
  return agree >= required;
}

// Independent support (options.independent_support; see the header): among the neighbours that are not matching
// partners of the point's view (bit k of `partner_slots` set = neighbors[k] is one), those whose depth agrees with
// X must be at least as many as those that could see X but have no depth there (unmatched, UnmatchedAt).
bool PassesIndependentSupport(const std::vector<SacView>& views, const std::vector<uint32_t>& neighbors,
                              const DepthLookup* hits, uint64_t partner_slots, const SacOptions& options) {
  int agree = 0, unmatched = 0;
  for (size_t k = 0; k < neighbors.size(); ++k) {
    const DepthLookup& hit = hits[k];
    if (!hit.inside || ((partner_slots >> k) & 1) != 0) continue;
    const SacView& b = views[neighbors[k]];
    const double tolerance = DepthToleranceM(b, hit.z_m, options);
    if (!IsValidDepth(hit.stored_depth_m)) {
      if (UnmatchedAt(b, hit, tolerance)) ++unmatched;
    } else if (std::abs(hit.stored_depth_m - hit.z_m) <= tolerance) {
      ++agree;
    }
  }
  return agree >= unmatched;
}

// Whether at least options.free_space_min_views of `judges` see through X (see the header). `neighbor_slot[b]`: the
// index of view b in the neighbour list whose lookups `neighbor_hits` holds, or -1 (those are not looked up again).
// The other judges are read through `ceilings` first (DepthCeiling): a view whose deepest valid depth around X's
// projection is not beyond X by more than the margin cannot see through X, and its depth map is not read.
// A judge sees through X only where every valid depth within options.free_space_window_px of X's projection does:
// one pixel of registration error must not turn the pixels next to an edge of that view into free space. Points
// on a foreground edge of their own view (core/depth_edge.h; within free_space_edge_band_px), where matchers fatten
// the foreground, are judged by the pixel alone (the see-through views' windows would hold their own fattening).
bool InFreeSpace(const std::vector<SacView>& views, uint32_t v, int row, int col, const Eigen::Vector3d& point,
                 double d, const std::vector<uint32_t>& judges, const std::vector<int>& neighbor_slot,
                 const DepthLookup* neighbor_hits, const std::vector<DepthCeiling>& ceilings,
                 const std::vector<double>& noise_factor, const SacOptions& options) {
  const double sigma_own = noise_factor.empty() ? 0.0 : DepthSigmaM(views, noise_factor, v, d);
  int window_px = -1;  // decided at the first view that sees through the pixel (most points have none)
  auto window = [&] {
    if (window_px < 0) {
      const double jump_m = options.depth_edge_jump_gsd * views[v].GsdAt(d);
      window_px = OnForegroundEdge(*views[v].depth, row, col, d, jump_m, options.free_space_edge_band_px)
                      ? 0
                      : options.free_space_window_px;
    }
    return window_px;
  };
  const int early_pass = options.free_space_early_pass_views;
  int count = 0;
  int asked = 0;  // judges other than v
  for (const uint32_t b : judges) {
    if (b == v) continue;
    // None of the first judges (the views that see the region best) saw through it: it passes (issue 13).
    if (count == 0 && early_pass > 0 && asked == early_pass) return false;
    ++asked;
    const bool looked_up = neighbor_slot[b] >= 0;
    DepthLookup hit =
        looked_up ? neighbor_hits[neighbor_slot[b]] : ProjectIntoDepth(views[b], views[b].PointInCamera(point));
    if (!hit.inside) continue;
    const double sigma_pair =
        noise_factor.empty() ? 0.0 : PairSigmaM(sigma_own, DepthSigmaM(views, noise_factor, b, hit.z_m));
    const double margin = std::max(DepthToleranceM(views[b], hit.z_m, options), options.free_space_sigmas * sigma_pair);
    if (!looked_up) {
      if (ceilings[b].At(hit.row, hit.col) - hit.z_m <= margin) continue;
      hit.stored_depth_m = views[b].depth->at(hit.row, hit.col);
    }
    if (!IsValidDepth(hit.stored_depth_m) || hit.stored_depth_m - hit.z_m <= margin) continue;
    const double z_m = hit.z_m;
    if (options.free_space_window_px > 0 &&
        AnyDepthInWindow(*views[b].depth, hit.row, hit.col, window(),
                         [&](float q) { return IsValidDepth(q) && q - z_m <= margin; })) {
      continue;
    }
    if (++count >= options.free_space_min_views) return true;
  }
  return false;
}

}  // namespace

PointVerdicts::PointVerdicts(const std::vector<SacView>& views, std::vector<std::vector<uint32_t>> neighbors,
                             ConsultedViews judges, std::vector<double> noise_factor,
                             const SacOptions& options)
    : views_(views),
      neighbors_(std::move(neighbors)),
      judges_(std::move(judges)),
      noise_factor_(std::move(noise_factor)),
      options_(options) {
  neighbor_slot_.assign(views.size(), std::vector<int>(views.size(), -1));
  memo_.resize(views.size());
  for (uint32_t v = 0; v < views.size(); ++v) {
    if (neighbors_[v].size() > kMaxJudgingViews) {
      throw std::invalid_argument("PointVerdicts: view " + std::to_string(v) + " has " +
                                  std::to_string(neighbors_[v].size()) + " neighbour views, at most " +
                                  std::to_string(kMaxJudgingViews) + " are supported");
    }
    for (size_t k = 0; k < neighbors_[v].size(); ++k) neighbor_slot_[v][neighbors_[v][k]] = static_cast<int>(k);
    // Which neighbours are matching partners of v (independent support), as a bit per neighbour slot.
    const std::vector<uint32_t>& partners = views[v].view.matching_partners;
    uint64_t slots = 0;
    for (size_t k = 0; k < neighbors_[v].size(); ++k) {
      if (std::binary_search(partners.begin(), partners.end(), views[neighbors_[v][k]].view.index)) {
        slots |= uint64_t{1} << k;
      }
    }
    partner_slots_.push_back(slots);
    // Value-initialised: every pixel starts "not judged" (0). Two pixels per byte.
    memo_[v].reset(new std::atomic<uint8_t>[(views[v].depth->num_pixels() + 1) / 2]());
  }
  ceilings_.resize(views.size());
  if (options_.free_space_min_views > 0) {
    tbb::parallel_for(size_t{0}, views.size(), [&](size_t v) { ceilings_[v] = DepthCeiling(*views[v].depth); });
  }
}

DepthCeiling::DepthCeiling(const DepthMap& depth)
    : blocks_((depth.width + kBlockPx - 1) / kBlockPx, (depth.height + kBlockPx - 1) / kBlockPx, 1,
              -std::numeric_limits<float>::infinity()) {
  for (int row = 0; row < depth.height; ++row) {
    float* deepest = &blocks_.at(row / kBlockPx, 0);
    for (int col = 0; col < depth.width; ++col) {
      const float d = depth.at(row, col);
      if (IsValidDepth(d)) deepest[col / kBlockPx] = std::max(deepest[col / kBlockPx], d);
    }
  }
}

PointVerdict PointVerdicts::At(uint32_t view, int row, int col) const {
  const size_t pixel = static_cast<size_t>(row) * views_[view].depth->width + col;
  std::atomic<uint8_t>& slot = memo_[view][pixel / 2];
  const int shift = (pixel % 2) * 4;
  const uint8_t known = (slot.load(std::memory_order_relaxed) >> shift) & 0xF;
  if (known != 0) return static_cast<PointVerdict>(known - 1);
  // Two threads may judge the same pixel at once; both set the same bits. The byte's other pixel is left as it is
  // (its bits are only ever set, from 0, to its one verdict).
  const PointVerdict verdict = Judge(view, row, col);
  slot.fetch_or(static_cast<uint8_t>((static_cast<uint8_t>(verdict) + 1) << shift), std::memory_order_relaxed);
  return verdict;
}

PointVerdict PointVerdicts::Judge(uint32_t v, int row, int col) const {
  const SacView& view = views_[v];
  const float d = view.depth->at(row, col);
  if (!IsValidDepth(d)) return PointVerdict::kInvalid;
  const Eigen::Vector3d point = PixelPoint(view, row, col, d);
  // Each point is looked up once in each neighbour; the free-space test reuses those lookups.
  const std::vector<uint32_t>& near = neighbors_[v];
  std::array<DepthLookup, kMaxJudgingViews> hits;
  // Projected into every neighbour first, read after: the reads' cache misses overlap (PrefetchDepthPixel).
  for (size_t k = 0; k < near.size(); ++k) {
    const SacView& b = views_[near[k]];
    hits[k] = ProjectIntoDepth(b, b.PointInCamera(point));
    if (hits[k].inside) PrefetchDepthPixel(b, hits[k].row, hits[k].col);
  }
  for (size_t k = 0; k < near.size(); ++k) {
    if (hits[k].inside) hits[k].stored_depth_m = views_[near[k]].depth->at(hits[k].row, hits[k].col);
  }
  if (!PassesOutlierTest(views_, v, d, near, hits.data(), noise_factor_, options_,
                         OnMatchedRim(view, row, col, options_))) {
    return PointVerdict::kOutlier;
  }
  if (options_.independent_support && !view.view.matching_partners.empty() &&
      !PassesIndependentSupport(views_, near, hits.data(), partner_slots_[v], options_)) {
    return PointVerdict::kOutlier;
  }
  if (options_.free_space_min_views > 0 &&
      InFreeSpace(views_, v, row, col, point, d, judges_.At(v, point), neighbor_slot_[v], hits.data(), ceilings_,
                  noise_factor_, options_)) {
    return PointVerdict::kFreeSpace;
  }
  return PointVerdict::kPasses;
}

}  // namespace sacfuse
