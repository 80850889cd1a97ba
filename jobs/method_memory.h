#pragma once
// Memory of the comparison methods beyond what tiles/memory_model.h estimates for SAC per depth pixel (12 B/px in
// a tile). They hold every view's colours with the views (3) and per-pixel marks or the computed normals of
// disparity_normal: 8 more, so 20 B/px as measured before SAC's labels and colours shrank. tsdf also holds its
// voxel grid, whose size follows the surface seen (about one band of 2 truncation / voxel voxels per voxel column),
// measured at ~50 B per depth pixel with voxel 1 GSD and truncation 4 GSD on the tiny and small blocks; it scales
// with truncation / voxel^3 (defaults: ~100 B/px).
#include <cstdint>

#include "config/job_config.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

// Extra bytes per depth pixel of fusion.method (0 for SAC).
uint64_t MethodExtraBytesPerDepthPixel(const FusionOptions& fusion);
// A tile's estimate for fusion.method: tile.memory_bytes plus the extra bytes of its window pixels.
uint64_t MethodTileBytes(const PlannedTile& tile, const FusionOptions& fusion);
// The TSDF voxel-grid limit of a job: tsdf.max_memory_gb, or resources.memory_gb when that is 0.
FusionOptions WithTsdfMemoryLimit(const JobConfig& config);

}  // namespace sacfuse
