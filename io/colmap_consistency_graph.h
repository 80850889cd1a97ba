#pragma once
// COLMAP dense-matching consistency graphs (stereo/consistency_graphs/<name>.<type>.bin, written by
// patch_match_stereo with --PatchMatchStereo.write_consistency_graph 1): an ASCII header "W&H&1&" then
// little-endian int32 runs (col, row, N, image_idx_1 .. image_idx_N) for pixels with N > 0 consistent images.
// Image indices are positions in the workspace's image order (COLMAP's mvs::Model), which ColmapWorkspace maps to
// view indices.
#include <string>
#include <vector>

#include "core/consistency_graph.h"

namespace sacfuse {

// Reads a graph; indices are returned as stored. Throws InputError naming the file for malformed content
// (runs past the end, pixels outside W x H, negative counts).
ConsistencyGraph ReadColmapConsistencyGraph(const std::string& path);
// Writes atomically (temporary name, fsync, rename).
void WriteColmapConsistencyGraph(const std::string& path, const ConsistencyGraph& graph);

}  // namespace sacfuse
