#include "core/multiray_fusion.h"

#include <chrono>
#include <cmath>

#include "core/option_check.h"
#include "core/ray_triangulation.h"
#include "core/reference_view_pass.h"

namespace sacfuse {

void ValidateMultirayOptions(const MultirayOptions& o) {
  OptionChecker c;
  c.Greater("MultirayOptions.depth_tolerance_gsd", o.depth_tolerance_gsd, 0.0);
  c.InRange("MultirayOptions.min_rays", o.min_rays, 2, 65);
  c.Greater("MultirayOptions.ray_sigma_px", o.ray_sigma_px, 0.0);
  c.AtLeast("MultirayOptions.depth_sigma_gsd", o.depth_sigma_gsd, 0.0);
  c.ThrowIfFailed("multiray options");
}

FusionStats RunMultirayFusion(const std::vector<SacView>& views, const MultirayOptions& options, PointSink& sink,
                              const ViewPlan* given_plan) {
  ValidateMultirayOptions(options);
  const auto start = std::chrono::steady_clock::now();
  const ViewPlan plan = given_plan != nullptr ? *given_plan : ViewPlanFromDepth(views, NeighborViewOptions{});
  CheckViewPlan(plan, views.size());
  enum { kTooFew = 0, kRays = 1, kSingular = 2 };

  const auto make_ray = [&](const SacView& view, const Eigen::Vector3d& point, double depth_m) {
    TriangulationRay ray;
    ray.origin = view.world_from_cam.translation;
    ray.direction = (point - ray.origin).normalized();
    ray.measured = point;
    const double gsd = view.GsdAt(depth_m);
    ray.lateral_sigma_m = options.ray_sigma_px * gsd;
    ray.along_sigma_m = options.depth_sigma_gsd * gsd;
    return ray;
  };
  const ReferencePixelFn fn = [&](uint32_t v, int row, int col, float depth, const Eigen::Vector3d& point,
                                  PixelMarks& marks, FusedPoint* out, PassCounters* counters) {
    thread_local std::vector<TriangulationRay> rays;
    struct Member {
      uint32_t view;
      int row, col;
    };
    Member members[64];
    int count = 0;
    rays.clear();
    rays.push_back(make_ray(views[v], point, depth));
    for (const uint32_t j : plan.neighbors[v]) {
      const DepthLookup hit = LookupDepth(views[j], point);
      if (!hit.inside || !IsValidDepth(hit.stored_depth_m)) continue;
      if (std::abs(hit.stored_depth_m - hit.z_m) > options.depth_tolerance_gsd * views[j].GsdAt(hit.z_m)) continue;
      if (count >= 64) break;
      members[count++] = {j, hit.row, hit.col};
      rays.push_back(make_ray(views[j], PixelPoint(views[j], hit.row, hit.col, hit.stored_depth_m),
                              hit.stored_depth_m));
    }
    if (static_cast<int>(rays.size()) < options.min_rays) {
      ++(*counters)[kTooFew];
      return false;
    }
    const std::optional<Eigen::Vector3d> x = TriangulateRays(rays);
    if (!x) {
      ++(*counters)[kSingular];
      return false;
    }
    std::array<int, 3> rgb_sum{};
    const auto add_colour = [&](const std::array<uint8_t, 3>& c) {
      for (int k = 0; k < 3; ++k) rgb_sum[k] += c[k];
    };
    add_colour(PixelColour(views[v], row, col));
    for (int m = 0; m < count; ++m) {
      add_colour(PixelColour(views[members[m].view], members[m].row, members[m].col));
      marks.Mark(members[m].view, members[m].row, members[m].col);
    }
    const int n = count + 1;
    out->point_in_world = *x;
    for (int k = 0; k < 3; ++k) out->rgb[k] = static_cast<uint8_t>((rgb_sum[k] + n / 2) / n);
    out->view_index = views[v].view.index;
    (*counters)[kRays] += static_cast<uint64_t>(n);
    return true;
  };
  FusionStats stats;
  RunReferenceViewPasses(views, plan, {"too_few_rays", "rays_triangulated", "singular"}, fn, sink, &stats);
  stats.stage_seconds.emplace_back(
      "fuse", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return stats;
}

}  // namespace sacfuse
