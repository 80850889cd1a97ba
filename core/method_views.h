#pragma once
// What the per-pixel comparison methods (consistency, disparity_normal, multiray) need besides the rasters: each
// view's neighbour views (where its points are reprojected), the order in which views are processed (which view
// keeps a point several views agree on), and small pixel helpers shared by all methods.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/backproject.h"
#include "core/sac_view.h"
#include "core/view_neighbors.h"

namespace sacfuse {

struct ViewPlan {
  std::vector<std::vector<uint32_t>> neighbors;  // per view (positions in the view vector), best first
  std::vector<uint32_t> order;                   // processing order: every view position exactly once
};

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
  return DepthPixelToWorld(view.depth_camera, view.world_from_cam, col, row, depth_m);
}

// PixelColour (core/sac_view.h): the colour of a depth pixel, the same rule as SAC's collapse.

}  // namespace sacfuse
