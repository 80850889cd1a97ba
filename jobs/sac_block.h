#pragma once
// SAC over a whole workspace held in memory: loads every view's depth map, image and superpixels (computing and
// caching superpixels as needed), then runs core's RunSacFusion. The tiled job system replaces "whole workspace"
// by per-tile windows; this is the untiled path.
#include <string>

#include "core/point.h"
#include "core/sac_fusion.h"
#include "io/depth_block.h"

namespace sacfuse {

struct SacBlockResult {
  SacStats stats;
  size_t superpixels_computed = 0;  // views whose superpixels were computed (the rest came from the cache)
  double superpixel_seconds = 0.0;
};

SacBlockResult FuseWorkspaceWithSac(const DepthBlock& input, const SacOptions& options,
                                    const std::string& superpixel_cache_dir, PointSink& sink,
                                    const SacProgress& progress = {});

}  // namespace sacfuse
