#pragma once
// `fusion.method: tsdf` — volumetric fusion by a truncated signed distance function, the SAC paper's reference
// [7] (Curless & Levoy 1996; as Open3D's scalable TSDF): every depth map is integrated into a sparse voxel grid
// (core/tsdf_volume.h: a hash map of 8^3-voxel blocks allocated within the truncation distance of observed
// points, so memory follows the surface), and the zero crossings of the fused distance field are the points.
// Views are integrated in input order. Each point takes its colour and LAS source view from the voxel nearer to
// its crossing, whose colour/source is the view that observed it near the surface with the smallest expected
// depth error (z^2 / focal at the voxel), so the source ids say which depth map a surface is best measured by.
// The output density is set by the voxel size (about one point per voxel of surface), not by the pixels.
#include <cstdint>
#include <vector>

#include "core/fusion_stats.h"
#include "core/method_views.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

struct TsdfOptions {
  double voxel_size_gsd = 1.0;   // voxel edge, in GSDs of the block (see gsd_m below). > 0
  // Truncation distance, in GSDs: 8 voxels at the default size, Open3D's default multiplier; measured on the
  // small block, 4 GSDs cost 10 F1 points at 2 x GSD (73.8 against 83.6), since with stereo noise of a few GSDs
  // the truncation clips the observations asymmetrically. > voxel_size_gsd
  double truncation_gsd = 8.0;
  double min_weight = 2.0;       // a crossing needs both voxels observed at least this often. >= 1
  double max_memory_gb = 0.0;    // the voxel grid of one run or tile may not exceed this, GiB (Error); 0 = no
                                 // limit here (jobs use resources.memory_gb). >= 0
};

// Throws ConfigError naming TsdfOptions.<field> for every invalid field (an invariant of the run; the YAML keys
// are checked by config/option_table.cc).
void ValidateTsdfOptions(const TsdfOptions& options);

// The block's GSD from the rasters: median over views of (median valid depth / focal of the depth raster), in
// metres; 0 when no view has a valid depth.
double MedianGsdFromDepth(const std::vector<SacView>& views);

// `gsd_m` <= 0: MedianGsdFromDepth(views). Jobs pass the block's GSD computed from its geometry, so that every
// tile uses the same voxel grid (voxels are aligned to multiples of the voxel size in world coordinates).
// Superpixels are not used (may be null). Counters: voxel_blocks, voxels (allocated).
// `region_xy`, when given, restricts the voxel grid (and so the points) to that XY box: a tile's halo.
FusionStats RunTsdfFusion(const std::vector<SacView>& views, const TsdfOptions& options, PointSink& sink,
                          double gsd_m = 0.0, const Box2d* region_xy = nullptr);

}  // namespace sacfuse
