#include "jobs/tile_queue.h"

#include <filesystem>

#include <spdlog/spdlog.h>

#include "config/result_settings.h"
#include "core/error.h"
#include "jobs/open_input.h"
#include "jobs/auto_tiling.h"
#include "jobs/fusion_methods.h"
#include "jobs/run_fusion.h"
#include "jobs/thread_limit.h"
#include "jobs/tile_claim.h"
#include "jobs/tile_marker.h"
#include "jobs/superpixel_cache.h"
#include "jobs/tiled_run.h"
#include "jobs/tile_fusion.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

// Opens the workspace and resolves an automatic tile size into *resolved; throws ConfigError for untiled jobs.
std::unique_ptr<DepthBlock> OpenTiledInput(const JobConfig& config, JobConfig* resolved) {
  ValidateJobConfig(config);
  std::unique_ptr<DepthBlock> input = OpenNonEmptyInput(config.input, "fuse", config.crs);
  *resolved = ResolveTiling(config, *input);
  if (resolved->tiling.tile_size_m <= 0) {
    throw ConfigError("not a tiled run: tiling.tile_size_m = 0 and the whole block fits in resources.memory_gb, so "
                      "it runs untiled (`sacfuse run`); set tiling.tile_size_m > 0 to cut it into tiles");
  }
  return input;
}

// The merged cloud's options (output.format); tiles are written with compressed = false (intermediate files).
LasWriterOptions FusedCloudOptions(const JobConfig& config, const TilePlan& plan) {
  LasWriterOptions las = MakeLasOptions(config);
  las.offset = SharedTileOffset(plan);
  return las;
}

LasWriterOptions TileLasOptions(const JobConfig& config, const TilePlan& plan) {
  LasWriterOptions las = FusedCloudOptions(config, plan);
  las.compressed = false;
  return las;
}

}  // namespace

TileWorkOutcome RunOneTile(const JobConfig& given, const std::string& id) {
  JobConfig config;
  const std::unique_ptr<DepthBlock> input = OpenTiledInput(given, &config);
  const ThreadLimit thread_limit(EffectiveThreads(config));
  const BlockIdentity identity = IdentifyBlock(*input);
  const TilePlan plan = SharedTilePlan(config, *input, identity.views);
  const PlannedTile* tile = nullptr;
  for (const PlannedTile& t : plan.tiles) {
    if (t.id == id && !t.views.empty()) tile = &t;
  }
  if (tile == nullptr) {
    throw ConfigError("--id " + id + ": not a tile with views of this job (see `sacfuse plan CONFIG --list`)");
  }
  const TileJob job{config, *input, plan, TileLasOptions(config, plan), TilesDir(config), ResultSettingsHash(config),
                    identity.views};
  fs::create_directories(job.tiles_dir);
  const TileInputs inputs = TileInputsOf(*tile, input->views(), identity.views);
  if (VerifyTileDone(job.tiles_dir, id, job.hash, true, &inputs).done) return {};
  RecordTiledRunState(config, plan, job.las, 1);
  return WorkOnTile(job, *tile, /*forced=*/false, nullptr, nullptr);
}

std::vector<std::string> MissingTiles(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                                      const std::vector<ViewIdentity>& identities) {
  const std::string tiles_dir = TilesDir(config);
  const std::string hash = ResultSettingsHash(config);
  std::vector<std::string> missing;
  for (const PlannedTile& tile : plan.tiles) {
    if (tile.views.empty()) continue;
    const TileInputs inputs = TileInputsOf(tile, input.views(), identities);
    if (!VerifyTileDone(tiles_dir, tile.id, hash, true, &inputs).done) missing.push_back(tile.id);
  }
  return missing;
}

MergeResult MergeTiledRun(const JobConfig& config, const TilePlan& plan, const LasWriterOptions& las,
                          const std::string& fused_las_path, const SacProgress& progress) {
  const std::string tiles_dir = TilesDir(config);
  std::vector<std::string> merge_order;  // LAS files of the tiles that have points, grid order
  for (const std::string& id : TileIdsWithViews(plan)) {
    const auto marker = ReadTileDoneMarker(tiles_dir, id);
    if (!marker) throw Error(TileDonePath(tiles_dir, id) + ": done marker vanished before the merge");
    if (marker->points > 0) merge_order.push_back(TileLasPath(tiles_dir, id));
  }
  const MergeResult merged = MergeTileLas(merge_order, fused_las_path, las, [&](size_t done, size_t n) {
    if (progress) progress("merge", done, n);
  });
  spdlog::info("merged {} tile files ({} points) into {}", merge_order.size(), merged.points, fused_las_path);
  return merged;
}

MergeJobOutcome MergeJob(const JobConfig& given) {
  JobConfig config;
  const std::unique_ptr<DepthBlock> input = OpenTiledInput(given, &config);
  const BlockIdentity identity = IdentifyBlock(*input);
  const TilePlan plan = SharedTilePlan(config, *input, identity.views);
  MergeJobOutcome out;
  out.fused_las_path = FusedLasPath(config);
  out.missing = MissingTiles(config, *input, plan, identity.views);
  if (!out.missing.empty()) return out;
  out.merged = MergeTiledRun(config, plan, FusedCloudOptions(config, plan), out.fused_las_path);
  return out;
}

}  // namespace sacfuse
