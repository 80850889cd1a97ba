#pragma once
// What the per-pixel comparison methods (consistency, disparity_normal, multiray) need besides the rasters: each
// view's neighbour views (where its points are reprojected), the order in which views are processed (which view
// keeps a point several views agree on), and small pixel helpers shared by all methods.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/sac_view.h"

namespace sacfuse {

// Neighbour views by the same rule as SAC's (core/view_neighbors.h): footprint boxes overlapping by at least
// min_footprint_overlap of the view's box, viewing directions within max_view_angle_deg, the best max_views by
// overlap x cos(angle), ties by index. The job fills these from fusion.max_neighbor_views,
// fusion.max_view_angle_deg and fusion.min_footprint_overlap, so every method reprojects into the same views.
struct NeighborViewOptions {
  int max_views = 10;                   // per view
  double max_view_angle_deg = 65.0;     // degrees
  double min_footprint_overlap = 0.05;  // fraction of the view's footprint box, 0-1
};

// XY box of a footprint, world metres.
struct FootprintBox {
  Eigen::Vector2d min = Eigen::Vector2d::Constant(1e300);
  Eigen::Vector2d max = Eigen::Vector2d::Constant(-1e300);
  bool empty() const { return !(min.x() < max.x() && min.y() < max.y()); }
  void Extend(const Eigen::Vector2d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
};

struct ViewPlan {
  std::vector<std::vector<uint32_t>> neighbors;  // per view (positions in the view vector), best first
  std::vector<uint32_t> order;                   // processing order: every view position exactly once
};

// neighbors[v] from footprint boxes and viewing directions (unit, world frame), both indexed like the views.
std::vector<std::vector<uint32_t>> NeighborsFromFootprints(const std::vector<FootprintBox>& boxes,
                                                           const std::vector<Eigen::Vector3d>& view_directions,
                                                           const NeighborViewOptions& options);

// Views sorted by expected depth uncertainty, most precise first: sigma_rel[v] ~ z^2 / focal (stereo
// sigma_z = z^2 sigma_d / (f B) at equal baselines, the criterion of SAC's quality unary); ties by position.
std::vector<uint32_t> PrecisionOrder(const std::vector<double>& sigma_rel);

// A plan from the rasters themselves: footprints from every 8th valid depth pixel in each direction, precision
// from each view's median sampled depth (z_med^2 / fx of its depth raster). Used when the caller has no plan of
// its own (unit tests); jobs plan from the block's geometry so that tiles and untiled runs agree.
ViewPlan ViewPlanFromDepth(const std::vector<SacView>& views, const NeighborViewOptions& options);

// Throws Error unless `plan` has a neighbour list per view and an order that is a permutation of the views.
void CheckViewPlan(const ViewPlan& plan, size_t num_views);

// World point of depth pixel (col, row) of a view at z-depth depth_m (through the pixel centre).
inline Eigen::Vector3d PixelPoint(const SacView& view, int row, int col, double depth_m) {
  return view.world_from_cam * view.depth_camera.Unproject(col + 0.5, row + 0.5, depth_m);
}

// PixelColour (core/sac_view.h): the colour of a depth pixel, the same rule as SAC's collapse.

}  // namespace sacfuse
