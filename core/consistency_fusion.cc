#include "core/consistency_fusion.h"

#include <chrono>
#include <cmath>

#include "core/option_check.h"
#include "core/reference_view_pass.h"

namespace sacfuse {

void ValidateConsistencyOptions(const ConsistencyOptions& o) {
  OptionChecker c;
  c.Require(o.depth_threshold_rel > 0.0 && o.depth_threshold_rel <= 0.5, "ConsistencyOptions.depth_threshold_rel",
            OptionChecker::ToString(o.depth_threshold_rel), "must be in (0, 0.5]");
  c.ThrowIfFailed("consistency options");
}

FusionStats RunConsistencyFusion(const std::vector<SacView>& views, const ConsistencyOptions& options,
                                 PointSink& sink, const ViewPlan* given_plan) {
  ValidateConsistencyOptions(options);
  const auto start = std::chrono::steady_clock::now();
  const ViewPlan plan = given_plan != nullptr ? *given_plan : ViewPlanFromDepth(views, NeighborViewOptions{});
  CheckViewPlan(plan, views.size());
  std::vector<size_t> rank(views.size());
  for (size_t i = 0; i < plan.order.size(); ++i) rank[plan.order[i]] = i;
  const double thr = options.depth_threshold_rel;
  enum { kRedundant = 0, kOccluded = 1 };

  const ReferencePixelFn fn = [&](uint32_t v, int row, int col, float, const Eigen::Vector3d& point,
                                  PixelMarks& marks, FusedPoint* out, PassCounters* counters) {
    for (const uint32_t j : plan.neighbors[v]) {
      if (rank[j] < rank[v]) continue;  // already emitted
      const DepthLookup hit = LookupDepth(views[j], point);
      if (!hit.inside || !IsValidDepth(hit.stored_depth_m)) continue;
      const double d = hit.stored_depth_m;
      if (std::abs(hit.z_m - d) <= thr * d) {
        marks.Mark(j, hit.row, hit.col);
        ++(*counters)[kRedundant];
      } else if (hit.z_m < d * (1.0 - thr)) {
        marks.Mark(j, hit.row, hit.col);
        ++(*counters)[kOccluded];
      }
    }
    out->point_in_world = point;
    out->rgb = PixelColour(views[v], row, col);
    out->view_index = views[v].view.index;
    return true;
  };
  FusionStats stats;
  RunReferenceViewPasses(views, plan, {"redundant_hits", "occluded_hits"}, fn, sink, &stats);
  stats.stage_seconds.emplace_back(
      "fuse", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return stats;
}

}  // namespace sacfuse
