#include "core/disparity_normal_fusion.h"

#include <chrono>
#include <cmath>

#include "core/depth_normals.h"
#include "core/option_check.h"
#include "core/reference_view_pass.h"

namespace sacfuse {
namespace {

Eigen::Vector3f NormalAt(const NormalMap& normals, int row, int col) {
  return {normals.at(row, col, 0), normals.at(row, col, 1), normals.at(row, col, 2)};
}

}  // namespace

void ValidateDisparityNormalOptions(const DisparityNormalOptions& o) {
  OptionChecker c;
  c.Greater("DisparityNormalOptions.disparity_threshold_px", o.disparity_threshold_px, 0.0);
  c.Require(o.normal_threshold_deg > 0.0 && o.normal_threshold_deg <= 180.0,
            "DisparityNormalOptions.normal_threshold_deg", OptionChecker::ToString(o.normal_threshold_deg),
            "must be in (0, 180]");
  c.InRange("DisparityNormalOptions.min_consistent_views", o.min_consistent_views, 1, 64);
  c.InRange("DisparityNormalOptions.normal_radius_px", o.normal_radius_px, 1, 10);
  c.ThrowIfFailed("disparity_normal options");
}

FusionStats RunDisparityNormalFusion(const std::vector<SacView>& views, const DisparityNormalOptions& options,
                                     PointSink& sink, const ViewPlan* given_plan) {
  ValidateDisparityNormalOptions(options);
  FusionStats stats;
  auto start = std::chrono::steady_clock::now();
  const ViewPlan plan = given_plan != nullptr ? *given_plan : ViewPlanFromDepth(views, NeighborViewOptions{});
  CheckViewPlan(plan, views.size());
  std::vector<NormalMap> normals;
  normals.reserve(views.size());
  for (const SacView& v : views) normals.push_back(PlaneFitNormalsInWorld(v, options.normal_radius_px));
  auto now = std::chrono::steady_clock::now();
  stats.stage_seconds.emplace_back("normals", std::chrono::duration<double>(now - start).count());
  start = now;

  const double cos_max = std::cos(options.normal_threshold_deg * M_PI / 180.0);
  enum { kInconsistent = 0, kMembers = 1 };
  const ReferencePixelFn fn = [&](uint32_t v, int row, int col, float, const Eigen::Vector3d& point,
                                  PixelMarks& marks, FusedPoint* out, PassCounters* counters) {
    const Eigen::Vector3f n_p = NormalAt(normals[v], row, col);
    if (n_p.squaredNorm() == 0.0f) {
      ++(*counters)[kInconsistent];
      return false;
    }
    const SacView& ref = views[v];
    const Eigen::Vector3d centre_i = ref.world_from_cam.translation;
    struct Member {
      uint32_t view;
      int row, col;
      Eigen::Vector3d point;
    };
    Member members[64];
    int consistent = 0;
    for (const uint32_t j : plan.neighbors[v]) {
      const DepthLookup hit = LookupDepth(views[j], point);
      if (!hit.inside || !IsValidDepth(hit.stored_depth_m)) continue;
      const double fb = ref.depth_camera.fx * (views[j].world_from_cam.translation - centre_i).norm();
      if (std::abs(fb / hit.z_m - fb / hit.stored_depth_m) > options.disparity_threshold_px) continue;
      const Eigen::Vector3f n_q = NormalAt(normals[j], hit.row, hit.col);
      if (n_q.squaredNorm() == 0.0f || n_p.dot(n_q) < cos_max) continue;
      if (consistent < 64) {
        members[consistent++] = {j, hit.row, hit.col, PixelPoint(views[j], hit.row, hit.col, hit.stored_depth_m)};
      }
    }
    if (consistent < options.min_consistent_views) {
      ++(*counters)[kInconsistent];
      return false;
    }
    Eigen::Vector3d sum = point;
    std::array<int, 3> rgb_sum{};
    const auto add_colour = [&](const std::array<uint8_t, 3>& c) {
      for (int k = 0; k < 3; ++k) rgb_sum[k] += c[k];
    };
    add_colour(PixelColour(ref, row, col));
    for (int m = 0; m < consistent; ++m) {
      sum += members[m].point;
      add_colour(PixelColour(views[members[m].view], members[m].row, members[m].col));
      marks.Mark(members[m].view, members[m].row, members[m].col);
    }
    const int n = consistent + 1;
    out->point_in_world = sum / n;
    for (int k = 0; k < 3; ++k) out->rgb[k] = static_cast<uint8_t>((rgb_sum[k] + n / 2) / n);
    out->view_index = ref.view.index;
    (*counters)[kMembers] += static_cast<uint64_t>(consistent);
    return true;
  };
  RunReferenceViewPasses(views, plan, {"inconsistent", "members_averaged"}, fn, sink, &stats);
  stats.stage_seconds.emplace_back(
      "fuse", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return stats;
}

}  // namespace sacfuse
