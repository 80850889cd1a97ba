#pragma once
// The merge step of a tiled run: the tile LAS files, in grid order, streamed chunk by chunk into one LasWriter
// (never the whole cloud in memory). Every tile must carry exactly the writer's scale and offset, so the
// stored integers are copied unchanged.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/las_writer.h"

namespace sacfuse {

struct MergeResult {
  uint64_t points = 0;
  std::vector<uint64_t> points_per_view;  // by view index (point source ID - 1)
};

// Merges `tile_las_paths` (in the order given) into `out_path`. `options.offset` must be set. Throws
// InputError naming a tile whose scale or offset differs, or that cannot be read; leaves no partial output.
MergeResult MergeTileLas(const std::vector<std::string>& tile_las_paths, const std::string& out_path,
                         const LasWriterOptions& options,
                         const std::function<void(size_t done, size_t total)>& progress = {});

}  // namespace sacfuse
