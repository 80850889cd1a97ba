#pragma once
// Dense-matching consistency graphs of a simulated workspace, as COLMAP's patch_match_stereo writes them with
// --PatchMatchStereo.write_consistency_graph 1: stereo/consistency_graphs/<name>.geometric.bin (format in
// io/colmap_consistency_graph.h), one per depth map and at its size. A post-pass over the depth maps already on
// disk, so it sees exactly what a matcher's output would be: the WRITTEN (noisy) depth and the WRITTEN poses.
//
// For a reference view i, the source views are the others whose depth-map point bounding boxes (world frame,
// padded by the depth tolerance) intersect i's; when more than max_source_views do, the ones sharing the largest
// horizontal box overlap are kept (patch-match.cfg's "__auto__, 20"). A valid pixel of i is back-projected with
// its depth and i's pose and projected into every source j; j is consistent when the projection lands inside j's
// depth map (z > 0) and j's depth at that pixel (nearest) agrees with the projected depth within
// max(relative_tolerance * depth, gsd_factor * local GSD), local GSD = depth / focal of the coarser of the two
// views. A pixel lists its consistent views by increasing image index, at most max_views_per_pixel.
//
// Memory: one reference depth map plus those of its source views at a time.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/consistency_graph.h"
#include "core/raster.h"
#include "core/view.h"

namespace sacfuse::sim {

struct ConsistencyGraphOptions {
  double relative_tolerance = 0.01;  // depth agreement as a fraction of the depth
  double gsd_factor = 2.0;           // ... or this many local GSDs, whichever is larger
  int max_source_views = 20;         // source views per reference view
  int max_views_per_pixel = 20;      // cap of a pixel's list
  int num_threads = 0;               // TBB threads over rows, 0 = all allowed; the output does not depend on it
};

struct ConsistencyGraphSummary {
  size_t num_graphs = 0;
  uint64_t valid_pixels = 0;        // valid depth pixels of all views
  uint64_t pixels_with_views = 0;   // ... that list >= 1 consistent view
  uint64_t entries = 0;             // image indices written in total
};

using ConsistencyProgress = std::function<void(size_t done, size_t total)>;

// One view of the in-memory core: its depth map, the camera AT DEPTH-MAP RESOLUTION and its pose.
struct DepthViewRef {
  const DepthMap* depth = nullptr;
  PinholeCamera camera;
  Rigid3d cam_from_world;
};

// The graph of views[ref] against the source views `sources` (positions in `views`, any order); the indices
// written are those positions. Entries of `views` not in `sources` (and not ref) may have a null depth.
ConsistencyGraph ComputeConsistencyGraph(size_t ref, const std::vector<DepthViewRef>& views,
                                         const std::vector<uint32_t>& sources, const ConsistencyGraphOptions& options);

// The post-pass on a workspace. `views` are its images in the sparse model's images order: the image index
// written for a view is its position in `views` (COLMAP's convention); intrinsics at image resolution (scaled to
// each depth map's size), WRITTEN poses. Reads stereo/depth_maps/<name>.geometric.bin and writes
// stereo/consistency_graphs/<name>.geometric.bin for every view. Throws InputError (depth maps) / Error.
ConsistencyGraphSummary WriteConsistencyGraphs(const std::string& workspace_dir, const std::vector<View>& views,
                                               const ConsistencyGraphOptions& options = {},
                                               const ConsistencyProgress& progress = {});

}  // namespace sacfuse::sim
