#pragma once
// SAC's tests of a depth pixel's own point X against the other views. The collapse (core/collapse.h) asks for the
// verdict of the pixels it would emit and of the other views' pixels it would drop a pixel in favour of: a pixel is
// dropped in favour of another view only where that view's pixel survives these tests, so removing outliers never
// leaves a hole that another view's pixel would have filled.
//
//  * Outliers (the paper is silent): X must agree with min(min_consistent_views, max(2, 1 + observers)) depth maps
//    (its own included) among its view's neighbours, where observers are the neighbours that agree or see through
//    the point; neighbours in which it is occluded cannot judge it. With estimated noise the requirement is also
//    capped at max(2, 1 + round(outlier_expected_factor x E)), E = the expected number of agreeing observers, sum of
//    erf(tolerance / (sqrt(2) sigma of the two depths' difference)).
//    Weak support: a neighbour that could observe X but has no depth at its projection, and no valid depth in front
//    of X within kDepthEdgeReachPx pixels (so X is not occluded there, core/depth_edge.h), is *unmatched*. Where a
//    neighbour is unmatched, X must agree with weak_support_min_views depth maps (off by default; 3 for raw stereo
//    output), at most min_consistent_views and 1 + observers + unmatched (a surface only one other view can see
//    still passes with that view). Unmatched views count in E as observers do. Why: a raw stereo depth and its partner view's depth come from the same match
//    and share its errors, so a blunder of single-pair depths in shadow or at the rim of what the matcher could match
//    "agrees" with one view while the others found nothing (Brighton Beach raw maps, docs/design.md).
//    The rim rule (weak_support_rim_px, 2; only with weak support on): a pixel within that many pixels of a hole of its
//    own depth map, on the rim of what the matcher matched, needs weak_support_min_views maps (at most
//    min_consistent_views) however few views observe it and whatever the noise cap allows: at the rim a matcher's
//    depths stray most, confirmed by the partner that shares the match (Brighton Beach raw maps, docs/design.md).
//    Independent support (independent_support, off by default; only for views whose matching partners the input
//    names, View::matching_partners): among the neighbours that are not matching partners of the point's view, those
//    that agree with X must be at least as many as those that could see X but have no depth there (unmatched, as
//    above). A partner's depth comes from the same image pair as the point's own and shares its matching errors, so
//    only other views' depths are independent evidence; where more independent views found nothing at X than
//    confirm it, the match is doubted (Brighton Beach raw maps, docs/design.md).
//  * Free space (visibility, Merrell et al., ICCV 2007): X is dropped when at least free_space_min_views of the
//    judging views (the combine views, up to 40) see through it: their depth at X's projection lies beyond X by more
//    than the tolerance and more than free_space_sigmas sigma of the two depths' difference, so X floats in space
//    they observed empty (fattened foreground at depth jumps, blunders, noisy canopy). Measured on aerial-bench
//    Montpellier (docs/design.md): asking also that more views see through X than agree with it removed nothing.
//    A view counts only where every valid depth within free_space_window_px (1) of X's projection sees through:
//    beside an edge of that view, a pixel of registration error would otherwise make a true roof edge free space
//    (aerial-bench St Barth F1 0.9413 -> 0.9431, docs/design.md). Not for points within free_space_edge_band_px (2) of a
//    foreground edge of their own view (core/depth_edge.h): there the foreground is fattened, and the see-through
//    views' windows would hold their own fattening, so those points are judged by the pixel alone.
//    The judges are asked in the consulted views' order (those that see the point's region best first), and a
//    point that none of the first free_space_early_pass_views (16) sees through passes without the rest (issue 13:
//    Dortmund tile 6_6 -11 % CPU; aerial-bench F1 within -0.0001 / +0.0003, free space +0.2 to +1.6 % of itself).
//
// Verdicts are judged on first ask and remembered (issue 13): with `collapse: best_view` about 70 % of the pixels
// are dropped in favour of another view's pixel before their own verdict matters, and judging every pixel up front
// (~40 depth reads each) was 45 % of SAC's time. A verdict is a function of its pixel only, so which thread judges
// it first, and when, changes nothing.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/consulted_views.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

// The deepest valid depth of each kBlockPx x kBlockPx block of a depth map (-infinity where a block has none): an
// upper bound on any pixel's stored depth that fits in cache (1/64 of the map). The free-space test reads it before
// the depth map itself and skips the read where even the deepest depth of the block cannot see through the point;
// the verdicts are exactly those of reading every pixel (issue 13).
class DepthCeiling {
 public:
  static constexpr int kBlockPx = 8;
  DepthCeiling() = default;
  explicit DepthCeiling(const DepthMap& depth);
  float At(int row, int col) const { return blocks_.at(row / kBlockPx, col / kBlockPx); }

 private:
  DepthMap blocks_;
};

enum class PointVerdict : uint8_t { kInvalid = 0, kOutlier = 1, kFreeSpace = 2, kPasses = 3 };

// The verdicts of every pixel of every view of `views` (a tile's halo pixels too: the collapse consults them).
// `neighbors[v]`: the views that judge v's outliers; `judges`: those that judge its free space (per pixel, the
// combine's; core/consulted_views.h); `noise_factor` as core/view_noise.h (empty = none). Keeps a reference to
// `views` (which must outlive it) and copies the rest.
// At() may be called from many threads at once.
class PointVerdicts {
 public:
  PointVerdicts(const std::vector<SacView>& views, std::vector<std::vector<uint32_t>> neighbors,
                ConsultedViews judges, std::vector<double> noise_factor, const SacOptions& options);

  // The verdict of depth pixel (row, col) of `view`, judged now if it was not yet.
  PointVerdict At(uint32_t view, int row, int col) const;

 private:
  PointVerdict Judge(uint32_t v, int row, int col) const;

  const std::vector<SacView>& views_;
  std::vector<std::vector<uint32_t>> neighbors_;
  ConsultedViews judges_;
  std::vector<std::vector<int>> neighbor_slot_;  // [v][b]: index of b in neighbors_[v], or -1
  std::vector<double> noise_factor_;
  std::vector<uint64_t> partner_slots_;  // [v]: bit k set when neighbors_[v][k] is a matching partner of v
  std::vector<DepthCeiling> ceilings_;  // per view (empty rasters when the free-space test is off)
  SacOptions options_;
  // Per view, row-major, two pixels per byte (the even pixel in the low 4 bits): 0 = not judged yet, else
  // 1 + PointVerdict. Half a byte per pixel (issue 13: a full byte was 19 MB of aerial Montpellier's 270 MB peak).
  std::vector<std::unique_ptr<std::atomic<uint8_t>[]>> memo_;
};

}  // namespace sacfuse
