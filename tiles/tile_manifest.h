#pragma once
// The state of a tiled run that is not per tile, in DIR/tiles/ (config/output_layout.h TilesDir):
//   manifest.json    TileManifest: the tiles with views (grid order), the shared scale and offset, the settings
//                    hash; written here, read by automatic tiling (the size of a run in progress), `sacfuse
//                    status` and the HTML report
//   run_config.yaml  the result-affecting settings of the last run (config/result_settings.h), to name changes
// Every tile LAS uses ONE scale (output.scale_m) and ONE offset: the project area's min corner (x, y) and the
// plan's z_min, each snapped down to a multiple of 1000 m, so tiles merge losslessly.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "config/job_config.h"
#include "io/las_writer.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

struct TileManifest {
  std::string config_hash;  // ResultSettingsHash of the run's config (tile size resolved)
  double tile_size_m = 0.0;
  int grid_x = 0, grid_y = 0;
  double scale_m = 0.0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  std::vector<std::string> tiles;  // ids of the tiles with views, grid order
  size_t tiles_without_views = 0;

  // The manifest of `plan` written with `las` (whose offset must be set) under the settings hash `hash`.
  static TileManifest Of(const TilePlan& plan, const LasWriterOptions& las, const std::string& hash);
  static std::string Path(const std::string& tiles_dir);  // <tiles_dir>/manifest.json
  // nullopt when there is none; throws Error naming the file when it is not JSON or has no "tiles" list (the
  // other fields default when absent).
  static std::optional<TileManifest> Read(const std::string& tiles_dir);
  void Write(const std::string& tiles_dir) const;  // atomically
};

// The shared offset of a plan's tiles (see above).
Eigen::Vector3d SharedTileOffset(const TilePlan& plan);
// Ids of the plan's tiles with views, grid order.
std::vector<std::string> TileIdsWithViews(const TilePlan& plan);

// Writes tiles/run_config.yaml (warning which result-affecting keys changed) and tiles/manifest.json.
// `las.offset` must be set.
void RecordTiledRunState(const JobConfig& config, const TilePlan& plan, const LasWriterOptions& las,
                         size_t tiles_to_compute);

}  // namespace sacfuse
