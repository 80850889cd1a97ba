#pragma once
// reference.las: the evaluation reference, streamed to disk in chunks.
//  - Synthetic scenes: LiDAR-like samples of the TRUE top surface on a jittered grid of spacing
//    1 / sqrt(density) (one uniform random point per grid cell), classification from the surface (2 ground,
//    5 vegetation, 6 building), RGB = albedo x 65535, intensity = albedo luminance.
//  - LiDAR scenes: the file's own points inside the area (RGB from the surface albedo when the file has none).
#include <cstdint>
#include <functional>
#include <string>

#include "tools/sim/surface.h"

namespace sacfuse::sim {

using ReferenceProgress = std::function<void(size_t done, size_t total)>;

uint64_t WriteSampledReference(const Surface& surface, const Box2d& area, double density_pts_m2, uint64_t key,
                               const std::string& path, const ReferenceProgress& progress = {});

uint64_t WriteLasReference(const std::string& las_path, const Surface& surface, const Box2d& area,
                           const std::string& path);

}  // namespace sacfuse::sim
