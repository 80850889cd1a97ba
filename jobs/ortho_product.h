#pragma once
// The true orthophoto of a run (output.ortho; docs/dsm-and-ortho.md): DIR/ortho.tif, an RGBA 8-bit Cloud Optimized
// GeoTIFF on the DSM's cells (or DIR/ortho.vrt over DIR/ortho/*.tif, the DSM's layout), made after the DSM is
// assembled, from the DSM product, the run's fused points and the input's original images:
//   - each cell's SAC-selected view is the source view (LAS point source ID - 1) of the cell's point whose height
//     is the cell's DSM height (the median point; among points of that height, the lowest view index);
//   - core/ortho_rule.h picks the view that colours the cell (the selected one when it sees the cell's surface
//     point, else the most nadir view that sees it; occlusion tested against the DSM) and samples its image
//     bilinearly at full resolution;
//   - cells without a DSM height, or that no view sees, are transparent (alpha 0).
// Bounded memory: the product is made block by block (io/raster_assembly.h's 2048 x 2048 blocks): per block the DSM
// window plus the occlusion halo, 8 bytes a cell for the selected views, one cloud reader per thread, and up to one
// decoded image per thread, as many as fit in a quarter of resources.memory_gb (at least one; each image a block
// needs is decoded once for that block). Each block's work runs on the
// job's threads: the clouds' points, the cells' views (by rows) and the colouring (by view); the result does not
// depend on the thread count. The ortho depends only on the DSM product, the
// points and the images, so a tiled run's ortho is that of its merged cloud and DSM, and a rerun writes the same
// bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "config/job_config.h"
#include "core/box2d.h"
#include "io/depth_block.h"
#include "jobs/dsm_product.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

// A point file of the run and the XY bounds of its points.
struct OrthoCloud {
  std::string path;
  Box2d bounds;
};

struct OrthoOutcome {
  bool written = false;
  std::string path;  // DIR/ortho.tif or DIR/ortho.vrt
  int64_t cols = 0, rows = 0;
  uint64_t cells_coloured = 0;
  uint64_t cells_selected_view = 0;  // coloured from the SAC-selected view
  uint64_t cells_other_view = 0;     // the selected view was occluded or absent: the most nadir view that sees it
  uint64_t cells_unseen = 0;         // with a DSM height, but no view sees them (transparent)
  uint64_t image_reads = 0;          // images decoded (once per block that needs them)
  size_t files = 0;
  double seconds = 0.0;
  double cpu_seconds = 0.0;     // of the process while making it (all threads)
  double peak_rss_mib = 0.0;    // process peak RSS after it
};

// The point files of a tiled run's done tiles (their markers name them and their bounds).
std::vector<OrthoCloud> TiledRunClouds(const JobConfig& config, const TilePlan& plan);
// An untiled run's fused cloud.
OrthoCloud FusedCloud(const std::string& path);

// Writes DIR/ortho.tif (or .vrt) on the cells of the DSM `dsm` names, or removes the ortho files when the run
// writes none (OrthoWanted false, or no DSM was written). Throws Error / InputError (an image that cannot be read).
OrthoOutcome MakeOrthoOfRun(const JobConfig& config, const DepthBlock& input, const DsmOutcome& dsm,
                            const std::vector<OrthoCloud>& clouds);

// Removes DIR/ortho.tif, DIR/ortho.vrt and DIR/ortho/.
void RemoveOrthoFiles(const JobConfig& config);

}  // namespace sacfuse
