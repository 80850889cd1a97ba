#pragma once
// The merge step of a tiled run: the tile files, in grid order, streamed chunk by chunk into one point cloud writer
// (never the whole cloud in memory). Every tile must carry exactly the writer's scale and offset, so the
// stored integers are copied unchanged. Into LAZ the tiles' full LAZ chunks are copied without decoding
// (LasWriter::AppendLaz): only each tile's last, shorter chunk is decoded and coded again. The cloud holds the
// tiles' full chunks in grid order, with the tiles' last points coded into chunks of their own as they gather
// (the same points as a point-by-point merge, deterministic, in another order). Into COPC every point is
// decoded and the octree built out of core (io/copc_writer.h). Then DIR/tiles.vpc indexes the tile files
// (io/vpc_writer.h).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "config/job_config.h"
#include "io/depth_block.h"
#include "io/point_cloud_writer.h"
#include "io/view_identity.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

struct MergeResult {
  uint64_t points = 0;
  std::vector<uint64_t> points_per_view;  // by view index (point source ID - 1), from the tiles' done markers
};

// Merges `tile_las_paths` (in the order given) into `out_path`; returns the points written. `options.offset`
// must be set. Throws InputError naming a tile whose scale or offset differs, or that cannot be read; leaves no
// partial output. `before_commit` (may be empty) runs when every point is written, before the file is renamed into
// place; what it throws leaves no output.
uint64_t MergeTileLas(const std::vector<std::string>& tile_las_paths, const std::string& out_path,
                      const CloudFileOptions& options,
                      const std::function<void(size_t done, size_t total)>& progress = {},
                      const std::function<void()>& before_commit = {});

// Streams the done tiles' files, grid order, into `fused_las_path`; `cloud.las.offset` must be the plan's shared
// offset (tiles/tile_manifest.h). Every tile with views must be done for THIS job: its marker carries the config's
// result-settings hash and the tile's inputs from `identities` (by view index) and its file's size and header
// agree (tiles/tile_marker.h VerifyTileDone without the checksum), else Error naming the tile and why, before
// anything is written; after the points are written and before the cloud is renamed into place, every marker
// must still be the one checked (another process rewriting a tile meanwhile fails the merge, naming it), then
// `before_commit` runs (may be empty; what it throws leaves no cloud). Then writes DIR/tiles.vpc over the tile
// files.
MergeResult MergeTiledRun(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                          const std::vector<ViewIdentity>& identities, const CloudFileOptions& cloud,
                          const std::string& fused_las_path,
                          const std::function<void(const std::string& stage, size_t done, size_t total)>& progress =
                              {},
                          const std::function<void()>& before_commit = {});

// Tiles with views whose done marker does not verify (full checksum, and inputs against `identities`, by view
// index), grid order.
std::vector<std::string> MissingTiles(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                                      const std::vector<ViewIdentity>& identities);

}  // namespace sacfuse
