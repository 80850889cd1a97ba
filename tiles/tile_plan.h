#pragma once
// `sacfuse plan`: which geo-tiles a job has, which views each tile needs and which window of each view's depth
// raster, and roughly how much memory a tile's rasters take. Built from the sparse model and the depth-map
// headers only (no raster is read), written as DIR/plan.json.
#include <cstdint>
#include <string>
#include <vector>

#include "config/job_config.h"
#include "io/depth_block.h"
#include "io/view_identity.h"
#include "tiling/tile_grid.h"
#include "tiling/tile_windows.h"

namespace sacfuse {

// Padding of the sparse points' 2nd..98th percentile height range, metres.
constexpr double kSparseHeightPaddingM = 10.0;

struct TileViewWindow {
  uint32_t view = 0;      // view index
  PixelWindow window;     // in the view's depth raster
};

struct PlannedTile {
  TileIndex index;
  std::string id;                      // "ix_iy"
  Box2d core, halo;                 // core is half-open [min, max)
  std::vector<TileViewWindow> views;   // in view order
  uint64_t window_pixels = 0;          // sum over views
  uint64_t memory_bytes = 0;           // estimate, TileBytes(window_pixels) (tiles/memory_model.h)
};

struct TilePlan {
  explicit TilePlan(const TileGrid& g) : grid(g) {}
  TileGrid grid;
  TilingOptions options;
  double z_min_m = 0.0, z_max_m = 0.0;
  std::string z_source;                       // DepthBlock::SceneHeightsSource | "config"
  std::vector<DepthRasterSize> depth_sizes;   // per view
  std::vector<PlannedTile> tiles;             // grid order
};

// Height range of the block: 2nd..98th percentile of the input's scene heights (DepthBlock::SceneHeights: sparse
// points, or a sample of the depth maps) padded by kSparseHeightPaddingM, or the options' z_min_m/z_max_m when
// there are none (a warning naming the input, io/input_warnings.h: footprints and tiles then hold only what lies
// in that range). *source names which.
void BlockHeightRange(const DepthBlock& input, const TilingOptions& options, double* z_min_m, double* z_max_m,
                      std::string* source);

// The plan of a workspace (reads only depth-map headers). Throws InputError when no view has a footprint.
TilePlan BuildTilePlan(const DepthBlock& input, const TilingOptions& options);

// JSON text of a plan (view names included; `config_hash`, the config's ResultSettingsHash, and `inputs_hash`,
// IdentitiesDigest of the views' identities, when not empty).
std::string TilePlanJson(const TilePlan& plan, const DepthBlock& input, const std::string& config_hash = "",
                         const std::string& inputs_hash = "");

// The plan shared by every worker of a job (`run`, `tile`, `merge`, `plan`): when <output.dir>/plan.json exists
// with the config's hash and the inputs' digest (`identities`: every view's, io/view_identity.h) it is used: the
// plan is rebuilt (deterministic, headers only) and must equal it, else Error; when the inputs changed (a pose,
// a depth map...) it is re-planned and rewritten (logged); otherwise this worker writes it atomically (racing
// writers produce the same content). *plan_path receives the file.
TilePlan SharedTilePlan(const JobConfig& config, const DepthBlock& input, const std::vector<ViewIdentity>& identities,
                        std::string* plan_path = nullptr);

}  // namespace sacfuse
