#pragma once
// `fusion.method: multiray` — the points of a correspondence group triangulated into one point from all their
// rays, the SAC paper's "multi-ray triangulation" baseline [35].
//
// Correspondence groups are built PER PIXEL by reprojection (not from SAC's superpixel nodes: a node's centroid
// ray and its correspondents' centroid rays pass through different surface points, up to a superpixel apart, so
// intersecting them would mostly measure the superpixel size; per-pixel groups need no superpixels either).
// Views are visited in the plan's order (jobs: most precise first). For each valid pixel p of the reference view
// i that no earlier group has used, with point X_i, X_i is projected into each neighbour view j; the pixel q it
// falls on (nearest) joins the group when j's depth there agrees with X_i's depth in j within
// depth_tolerance_gsd local GSDs (SAC's "same surface" rule). Each member k contributes the ray from its camera
// centre C_k through its own measured point X_k (its pixel centre at its own depth). Groups with at least
// min_rays rays (the reference's included) are triangulated (core/ray_triangulation.h): the point nearest to all
// rays, each weighted by its precision across (ray_sigma_px pixels at the member's GSD), plus each member's depth
// along its ray as a weaker observation (depth_sigma_gsd GSDs; 0 = rays only, the pure intersection). The
// member pixels are marked used, so they seed no group of their own later (as the paper's groups, each surface
// point is triangulated once). Colour: the mean of the members' colours; source view: the reference view i.
// Note what reprojected correspondences imply: member q is where X_i projects, rounded to a pixel, so the rays
// of the group pass within half a pixel of X_i; the depth terms carry the members' own depth measurements.
#include "core/fusion_stats.h"
#include "core/method_views.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

struct MultirayOptions {
  double depth_tolerance_gsd = 3.0;  // a neighbour's pixel joins the group within this many local GSDs. > 0
  int min_rays = 2;                  // smaller groups are dropped (one ray cannot be triangulated). [2, 65]
  double ray_sigma_px = 0.29;        // precision across a ray: pixel quantisation 1/sqrt(12) px. > 0
  double depth_sigma_gsd = 2.0;      // precision of a member's depth along its ray, local GSDs; 0 = rays only
};

// Throws ConfigError naming MultirayOptions.<field> for every invalid field (an invariant of the run; the YAML
// keys are checked by config/option_table.cc).
void ValidateMultirayOptions(const MultirayOptions& options);

// `plan` null = ViewPlanFromDepth(views, NeighborViewOptions{}). Superpixels are not used (may be null).
// Counters: too_few_rays (dropped), rays_triangulated (members over all emitted points, reference included),
// singular (dropped: parallel rays without depth terms), skipped_marked (pixels used by an earlier group).
FusionStats RunMultirayFusion(const std::vector<SacView>& views, const MultirayOptions& options, PointSink& sink,
                              const ViewPlan* plan = nullptr);

}  // namespace sacfuse
