#pragma once
// The block-level geometry the comparison methods need, computed from the views' poses, the depth raster sizes
// and the block's height range alone (no raster is read), so untiled runs and every tile use the same neighbour
// views, processing order and voxel size: the results of tiled and untiled runs then differ only near tile
// borders (halo context), not in which views a pixel is compared with.
#include <cstdint>
#include <vector>

#include "core/method_views.h"
#include "core/sac_options.h"
#include "core/view.h"
#include "io/depth_block.h"

namespace sacfuse {

struct MethodGeometry {
  ViewPlan plan;       // neighbours and order over all views of the block (view index = position)
  double gsd_m = 0.0;  // the block's GSD: median over views of the principal ray's depth / focal (depth raster)
};

// Footprint boxes: each view's footprint on the planes z_min and z_max (tiling/footprint.h); directions: the
// viewing directions; precision per view: z^2 / fx with z the depth at which the principal ray meets the
// reference plane and fx the focal length at depth-raster resolution (views whose principal ray misses the plane
// go last). The reference plane is the median height of the input's scene points (sparse tie points), or
// (z_min + z_max) / 2 without them.
MethodGeometry BlockMethodGeometry(const DepthBlock& input, const std::vector<DepthRasterSize>& depth_sizes,
                                   double z_min_m, double z_max_m, const NeighborViewOptions& options);

// The block's GSD alone (MethodGeometry::gsd_m, without the neighbour plan), metres; 0 when no view looks down.
double BlockDepthGsd(const DepthBlock& input, const std::vector<DepthRasterSize>& depth_sizes, double z_min_m,
                     double z_max_m);

// The plan restricted to `view_ids` (a tile's views, ascending): positions renumbered to the subset, neighbours
// outside it dropped, the order kept.
ViewPlan SubsetViewPlan(const ViewPlan& block_plan, const std::vector<uint32_t>& view_ids);

// fusion.max_neighbor_views, fusion.max_view_angle_deg, fusion.min_footprint_overlap.
NeighborViewOptions NeighborOptionsOf(const SacOptions& sac);

}  // namespace sacfuse
