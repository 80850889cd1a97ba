#pragma once
// A tiled SAC run with per-tile outputs and resume (tiling.tile_size_m > 0). State lives in DIR/tiles/:
//   run_config.yaml  the result-affecting settings of the last run (config/result_settings.h), to name changes
//   manifest.json    the tiles with views (grid order), the shared scale and offset, the settings hash
//   <id>.las / <id>.done.json / <id>.failed.json   see jobs/tile_marker.h
// Every tile LAS uses ONE scale (output.scale_m) and ONE offset: the project area's min corner (x, y) and the
// plan's z_min, each snapped down to a multiple of 1000 m, so tiles merge losslessly.
// A run deletes leftover "*.tmp-*" files, skips tiles whose done marker verifies, computes the rest (a tile that
// throws gets a failed marker; the others go on), and, when every tile with views is done, merges the tile
// files in grid order into DIR/fused.las.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config/job_config.h"
#include "io/colmap_workspace.h"
#include "io/las_writer.h"
#include "jobs/sac_block.h"
#include "jobs/tile_plan.h"

namespace sacfuse {

struct TiledRunOutcome {
  SacBlockResult block;  // SAC stats summed over the tiles computed by this invocation
  size_t tiles_with_views = 0;
  size_t tiles_computed = 0;                                // this invocation (including failed attempts)
  size_t tiles_skipped = 0;                                 // verified done, not recomputed
  std::vector<std::pair<std::string, std::string>> failed;  // tile id, reason
  bool merged = false;                                      // DIR/fused.las written
  uint64_t merged_points = 0;
  std::vector<uint64_t> points_per_view;  // of the merged cloud, by view index
};

std::string TilesDir(const JobConfig& config);
// The shared offset of a plan's tiles (see above).
Eigen::Vector3d SharedTileOffset(const TilePlan& plan);
// Ids of the plan's tiles with views, grid order.
std::vector<std::string> TileIdsWithViews(const TilePlan& plan);

// `rerun_ids` (already validated against TileIdsWithViews) are recomputed even when done.
TiledRunOutcome RunTiledSac(const JobConfig& config, const ColmapWorkspace& workspace, const TilePlan& plan,
                            const std::vector<std::string>& rerun_ids, LasWriterOptions las_options,
                            const std::string& fused_las_path, const SacProgress& progress = {});

}  // namespace sacfuse
