#pragma once
// SAC tile by tile (tiling.tile_size_m > 0): each tile loads only the windows of its views' depth maps,
// superpixel labels and colours that its halo box needs, runs core's RunSacFusion on them, and keeps only the
// points whose XY lies in the tile's half-open core, so the tiles stitch into one cloud without seams or
// duplicates. Tiles run one after another in grid order and stream into one sink (the job's one LAS writer).
#include <string>

#include "core/point.h"
#include "core/sac_fusion.h"
#include "io/colmap_workspace.h"
#include "jobs/sac_block.h"
#include "jobs/tile_plan.h"

namespace sacfuse {

struct TiledSacResult {
  SacBlockResult block;           // stats summed over tiles (pixels, nodes and points count every tile's halo)
  size_t tiles_run = 0;           // tiles with at least one view
  uint64_t points_in_cores = 0;   // points kept (written to the sink)
  uint64_t points_outside_core = 0;  // emitted in a tile's halo, left to the neighbouring tile
};

TiledSacResult FuseWorkspaceTiled(const ColmapWorkspace& workspace, const TilePlan& plan, const SacOptions& options,
                                  const std::string& superpixel_cache_dir, PointSink& sink,
                                  const SacProgress& progress = {});

}  // namespace sacfuse
