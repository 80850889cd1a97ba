#pragma once
// The per-tile fusion step, injected into the tile worker and scheduler (tiles/tile_worker.h,
// tiles/tile_scheduler.h), which know nothing about fusion methods, view sources or caches: jobs implements it
// (jobs/tile_fusion.h MethodTileFuser: any fusion.method through FuseViews).
#include <cstdint>
#include <vector>

#include "core/fusion_stats.h"
#include "core/point.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

// What fusing one tile reports.
struct TileFused {
  // Per-view vectors indexed like view_ids; input counts only the valid pixels whose own point the tile owns.
  FusionStats stats;
  std::vector<uint32_t> view_ids;  // the block's index of each view the tile loaded
  uint64_t points_written = 0;     // to the sink: the points of the tile's core
  std::vector<uint64_t> points_per_view;  // of points_written, by the block's view index
  uint64_t points_not_owned = 0;   // left to the neighbouring tiles
};

class TileFuser {
 public:
  virtual ~TileFuser() = default;
  // The tile's memory estimate: the out-of-memory guard refuses it above the tile pool, and memory admission
  // reserves it while the tile runs.
  virtual uint64_t TileBytes(const PlannedTile& tile) const = 0;
  // Makes the caches the tile's views lack (a worker that runs single tiles: `sacfuse tile --id`).
  virtual void PrepareTile(const PlannedTile& tile) = 0;
  // Fuses the tile (which has views) and writes the points of its core to `sink`. Called from several worker
  // threads at once; throws on unreadable inputs.
  virtual TileFused Fuse(const PlannedTile& tile, PointSink& sink) = 0;
};

}  // namespace sacfuse
