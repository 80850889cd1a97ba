#include "core/collapse.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>

#include "core/combine_anchors.h"
#include "core/depth_combine.h"
#include "core/method_views.h"
#include "core/patch_grid.h"
#include "core/redundancy.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

// Pixels are visited in patches (core/patch_grid.h); the points of a band of patches are put back into row order
// before they are written, so the output is that of a row-by-row visit.
constexpr int kPatchRows = 32;
constexpr int kPatchCols = 64;
// Bands in flight at once (computed, or waiting to be written), each holding its emitted points until it is
// written: with 32 a 1600-pixel-wide nadir view held 39 MB of points (aerial-bench Montpellier medium, issue 13);
// 8 bands still give each thread dozens of patches.
constexpr int kBandsInFlight = 8;
constexpr int kMaxCoverageHops = 4;  // chains of choices longer than this are treated as not covering


// Whether view `target` emits the surface at a pixel of view v (depth d): its depth agrees within the tolerance,
// or, with estimated noise factors, within coverage_tolerance_sigmas sigma of the difference of the two depths.
bool CoverageAgrees(const std::vector<SacView>& views, uint32_t v, double d, uint32_t target, const DepthLookup& hit,
                    const std::vector<double>& noise_factor, const SacOptions& options) {
  if (DepthAgrees(views[target], hit, options)) return true;
  if (noise_factor.empty() || options.coverage_tolerance_sigmas <= 0 || !hit.inside ||
      !IsValidDepth(hit.stored_depth_m)) {
    return false;
  }
  return AgreeWithinSigmas(hit.stored_depth_m - hit.z_m, DepthSigmaM(views, noise_factor, v, d),
                           DepthSigmaM(views, noise_factor, target, hit.z_m), options.coverage_tolerance_sigmas);
}

// Whether the view `label` that the pixel's cluster chose (or the view its cluster there chose, up to
// kMaxCoverageHops hops) emits the pixel's surface: every hop agrees with the point (CoverageAgrees), the chain
// ends in a cluster that chose its own view, and every pixel of the chain passes its point tests. The verdicts are
// asked last, once the chain's cheap checks hold: a verdict costs ~45 depth reads, a hop one.
bool ChoiceCovers(const std::vector<SacView>& views, uint32_t v, const Eigen::Vector3d& point, double d,
                  uint32_t label, const NodeTable& nodes, const NodeLabels& chosen_view,
                  const std::vector<double>& noise_factor, const PointVerdicts& verdicts, const SacOptions& options) {
  struct Hop {
    uint32_t view;
    int row, col;
  };
  std::array<Hop, kMaxCoverageHops> hops;
  int num_hops = 0;
  uint32_t target = label;
  bool covered = false;
  for (int hop = 0; hop < kMaxCoverageHops && target != v; ++hop) {
    const SacView& tv = views[target];
    const DepthLookup hit = LookupDepth(tv, point);
    if (!CoverageAgrees(views, v, d, target, hit, noise_factor, options)) return false;
    hops[num_hops++] = {target, hit.row, hit.col};
    const uint32_t next =
        chosen_view.At(nodes.Id(target, static_cast<uint32_t>(tv.superpixels->label(hit.row, hit.col))));
    if (next == target) {
      covered = true;
      break;
    }
    target = next;
  }
  for (int i = 0; covered && i < num_hops; ++i) {
    covered = verdicts.At(hops[i].view, hops[i].row, hops[i].col) == PointVerdict::kPasses;
  }
  return covered;
}

}  // namespace

CollapseStats EmitView(uint32_t v, const std::vector<SacView>& views, const NodeTable& nodes,
                       const NodeLabels& chosen_view, const ConsultedViews& redundancy_judges,
                       const ConsultedViews& combine_views,
                       const std::vector<double>& noise_factor, const PointVerdicts& verdicts,
                       const SacOptions& options, const OwnedRegion& owner, const RgbImage* colours,
                       PointSink& sink) {
  const SacView& view = views[v];
  const DepthMap& depth = *view.depth;
  const PatchGrid grid(depth.height, depth.width, kPatchRows, kPatchCols);
  const int patches_per_band = grid.patches_per_band();
  CollapseStats total;
  const bool combine = options.combine == "average";
  DepthCombineOptions combine_options;
  combine_options.gate_gsd = options.combine_gate_gsd;
  combine_options.gate_sigmas = options.combine_gate_sigmas;
  combine_options.slope_step_sigmas = options.combine_slope_step_sigmas;
  combine_options.weights = options.combine_weights == "equal"   ? CombineWeights::kEqual
                           : options.combine_weights == "noise" ? CombineWeights::kNoise
                                                                : CombineWeights::kView;
  combine_options.surface = options.combine_surface == "secant" ? CombineSurface::kSecant : CombineSurface::kPlane;
  combine_options.passes = options.combine_passes;
  combine_options.later_pass_gate = options.combine_later_pass_gate;
  combine_options.later_pass_min_shift_gsd = options.combine_later_pass_min_shift_gsd;
  const bool best_view = options.collapse == "best_view";
  const bool collapse_none = options.collapse == "none";
  // Per patch of the batch: its points in row order and the row of each.
  struct PatchOutput {
    std::vector<FusedPoint> points;
    std::vector<int> rows;
    CollapseStats stats;
  };
  std::vector<FusedPoint> band_points;
  const bool anchored = combine && options.combine_anchors;

  auto process_patch = [&](const PixelWindow& patch, PatchOutput& result) {
    std::vector<FusedPoint>& out = result.points;
    CollapseStats& stats = result.stats;
    out.clear();
    result.rows.clear();
    stats = CollapseStats{};
    const WindowOwnership ownership = ClassifyWindow(view, patch, owner);
    if (ownership.kind == WindowOwnership::kNone) {
      stats.not_owned = ownership.valid_pixels;
      return;
    }
    // With combine_anchors, the emitted pixels that are not anchors wait for the patch's anchors
    // (core/combine_anchors.h): their point's index in `out`, pixel, depth and node.
    CombineAnchors anchors(anchored ? patch : PixelWindow{});
    struct Pending {
      size_t index;
      int row, col;
      float depth;
      uint32_t node_id;
    };
    std::vector<Pending> pending;
    for (int row = patch.row_begin; row < patch.row_end; ++row) {
      for (int col = patch.col_begin; col < patch.col_end; ++col) {
        const float d = depth.at(row, col);
        if (!IsValidDepth(d)) continue;
        const Eigen::Vector3d point = PixelPoint(view, row, col, d);
        if (ownership.kind == WindowOwnership::kSome && !owner.Contains(point)) {
          ++stats.not_owned;
          continue;
        }
        ++stats.input_pixels;

        // Whether another view emits this surface, before the pixel's own verdict: most pixels are dropped here,
        // and their own tests (core/point_verdicts.h) are then never judged. Emitted: own verdict passes, not
        // redundant, not covered, whatever the order; only which counter a dropped pixel lands in depends on it.
        // The better view is asked first: the pixel it drops a pixel for is the most precise one there, which is
        // usually emitted and so judged anyway, where the chain's target is often itself redundant and would be
        // judged for nothing.
        if (best_view && BetterViewEmits(views, v, point, d, redundancy_judges.At(v, point), noise_factor, nodes,
                                         chosen_view, verdicts, options)) {
          ++stats.redundant;
          continue;
        }
        const uint32_t node_id = nodes.Id(v, static_cast<uint32_t>(view.superpixels->label(row, col)));
        const uint32_t label = collapse_none ? v : chosen_view.At(node_id);
        if (label != v) {
          if (ChoiceCovers(views, v, point, d, label, nodes, chosen_view, noise_factor, verdicts, options)) {
            ++stats.collapsed;
            continue;
          }
          ++stats.kept_uncovered;
        }
        const PointVerdict verdict = verdicts.At(v, row, col);
        if (verdict == PointVerdict::kOutlier) {
          ++stats.outliers;
          continue;
        }
        if (verdict == PointVerdict::kFreeSpace) {
          ++stats.free_space;
          continue;
        }
        FusedPoint p;
        p.point_in_world = point;
        if (anchored && !anchors.IsAnchor(row, col)) {
          pending.push_back({out.size(), row, col, d, node_id});
        } else if (combine) {
          const Eigen::Vector3d plane_normal = nodes.nodes[node_id].normal_in_world.cast<double>();
          const CombinedDepth refined = CombineDepth(views, v, col + 0.5, row + 0.5, d, combine_views.At(v, point),
                                                     noise_factor, combine_options, plane_normal);
          if (anchored) anchors.Set(row, col, refined);
          p.point_in_world = PixelPoint(view, row, col, refined.depth_m);
        }
        p.rgb = PixelColour(colours, depth, row, col);
        p.view_index = view.view.index;
        out.push_back(p);
        result.rows.push_back(row);
      }
    }
    for (const Pending& q : pending) {
      const Eigen::Vector3d plane_normal = nodes.nodes[q.node_id].normal_in_world.cast<double>();
      double depth_m = 0.0;
      if (anchors.Interpolate(views, v, q.row, q.col, q.depth, noise_factor, combine_options, plane_normal,
                              &depth_m)) {
        ++stats.interpolated;
      } else {
        const CombinedDepth exact =
            CombineDepth(views, v, q.col + 0.5, q.row + 0.5, q.depth, combine_views.At(v, out[q.index].point_in_world),
                         noise_factor, combine_options, plane_normal);
        anchors.Set(q.row, q.col, exact);
        depth_m = exact.depth_m;
      }
      out[q.index].point_in_world = PixelPoint(view, q.row, q.col, depth_m);
    }
    stats.emitted = out.size();
  };

  // The bands flow through a pipeline (issue 48): a band's patches are processed in parallel, and each band is
  // put back into row order and written by one serial, in-order step while the next bands are computed, so the
  // writing (LAS/LAZ encoding, I/O) overlaps the fusion instead of holding up every thread, and no thread waits at a
  // batch's end. A band's slot is free again when the band kBandsInFlight before it has been written.
  std::vector<std::vector<PatchOutput>> slots(kBandsInFlight, std::vector<PatchOutput>(patches_per_band));
  int next_band = 0;
  tbb::parallel_pipeline(
      kBandsInFlight,
      tbb::make_filter<void, int>(tbb::filter_mode::serial_in_order,
                                  [&](tbb::flow_control& flow) {
                                    if (next_band == grid.bands()) flow.stop();
                                    return next_band++;
                                  }) &
          tbb::make_filter<int, int>(tbb::filter_mode::parallel,
                                     [&](int b) {
                                       std::vector<PatchOutput>& band = slots[b % kBandsInFlight];
                                       tbb::parallel_for(0, patches_per_band, [&](int p) {
                                         process_patch(grid.Patch(b * patches_per_band + p), band[p]);
                                       });
                                       return b;
                                     }) &
          tbb::make_filter<int, void>(tbb::filter_mode::serial_in_order, [&](int b) {
            // Row order: each patch holds its rows in order, and the patches of a band lie left to right.
            std::vector<PatchOutput>& band = slots[b % kBandsInFlight];
            std::vector<size_t> next(patches_per_band, 0);
            band_points.clear();
            for (int row = grid.BandRowBegin(b); row < grid.BandRowEnd(b); ++row) {
              for (int p = 0; p < patches_per_band; ++p) {
                for (size_t& k = next[p]; k < band[p].points.size() && band[p].rows[k] == row; ++k) {
                  band_points.push_back(band[p].points[k]);
                }
              }
            }
            if (!band_points.empty()) sink.Write(band_points.data(), band_points.size());
            for (int p = 0; p < patches_per_band; ++p) total += band[p].stats;
          }));
  return total;
}

}  // namespace sacfuse
