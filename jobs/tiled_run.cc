#include "jobs/tiled_run.h"

#include <chrono>
#include <optional>

#include <spdlog/spdlog.h>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "core/error.h"
#include "io/test_pause.h"
#include "jobs/auto_tiling.h"
#include "jobs/cluster_table_cache.h"
#include "jobs/fusion_methods.h"
#include "jobs/las_options.h"
#include "jobs/tile_fusion.h"
#include "tiles/memory_model.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_merge.h"

namespace sacfuse {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Stage 2: the caches of every view the tiles read, before any tile runs.
void MakeViewCaches(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                    const std::vector<ViewIdentity>& identities, bool superpixels, const TileWorkList& work,
                    const StageProgress& progress, size_t views_in_flight, TiledRunOutcome* out) {
  const auto start = std::chrono::steady_clock::now();
  out->superpixels_computed = EnsureTiledSuperpixels(input, plan, config.fusion.sac, SuperpixelCacheDir(config),
                                                     identities, progress, nullptr, superpixels, views_in_flight);
  out->superpixel_seconds = SecondsSince(start);
  if (superpixels) {
    spdlog::info("superpixels: {} computed, {} reused ({:.1f} s); {} of {} tiles to compute",
                 out->superpixels_computed, input.views().size() - out->superpixels_computed,
                 out->superpixel_seconds, work.todo.size(), work.tiles_with_views);
  } else {
    spdlog::info("colour caches checked ({:.1f} s; no superpixels for {}); {} of {} tiles to compute",
                 out->superpixel_seconds, NameOf(config.fusion.method), work.todo.size(), work.tiles_with_views);
  }
}

}  // namespace

TiledRunOutcome RunTiledJob(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                            const std::vector<ViewIdentity>& identities,
                            const std::vector<std::string>& rerun_ids, const std::string& fused_las_path,
                            const StageProgress& progress, size_t views_in_flight,
                            const std::vector<ViewIdentity>* pinned, StageClock* clock) {
  const auto mark = [clock](const char* stage) {
    if (clock != nullptr) clock->Mark(stage);
  };
  const FusionNeeds needs = MakeFusionMethod(config.fusion)->needs();
  if (needs.consistency_graphs) {
    throw ConfigError("fusion.correspondence = dense: not supported by tiled runs yet");
  }
  TileJob job{config, input, plan, TileCloudOptions(config, plan), TilesDir(config), ResultSettingsHash(config),
              identities, /*caches_ready=*/true, {}};
  const std::optional<DsmGrid> dsm = DsmGridOf(config, input, plan.grid.area());
  std::optional<DsmTileProduct> dsm_product;
  if (dsm) job.products.push_back(&dsm_product.emplace(*dsm));

  TiledRunOutcome out;
  const TileWorkList work = ListTileWork(job, rerun_ids);
  out.tiles_with_views = work.tiles_with_views;
  out.tiles_skipped = work.tiles_skipped;
  out.tiles_rerun_for_inputs = work.rerun_for_inputs;
  RecordTiledRunState(config, plan, job.cloud.las, work.todo.size());
  mark("tile plan");
  if (!work.todo.empty()) {
    MakeViewCaches(config, input, plan, identities, needs.superpixels, work, progress, views_in_flight, &out);
    mark("superpixels");
  }

  ClusterTableCache cluster_cache(ClusterCacheBudgetBytes(MemoryBudgetBytes(config.resources.memory_gb)));
  MethodTileFuser fuser(config, input, plan, identities, &cluster_cache);
  TileStageOutcome tiles = RunTileWork(job, work, EffectiveThreads(config), fuser, progress);
  out.stats = std::move(tiles.stats);
  out.tiles_computed = tiles.tiles_computed;
  out.failed = std::move(tiles.failed);
  out.tiles_seconds = tiles.seconds;
  mark("tiles");
  if (!out.failed.empty()) return out;

  PauseAtTestPoint("run:before_merge");
  if (pinned != nullptr) CheckInputsUnchanged(input, *pinned);
  const auto merge_start = std::chrono::steady_clock::now();
  const MergeResult merged =
      MergeTiledRun(config, input, plan, identities, FusedCloudOptions(config, plan), fused_las_path, progress);
  out.merge_seconds = SecondsSince(merge_start);
  mark("merge");
  out.merged = true;
  out.merged_points = merged.points;
  out.points_per_view = merged.points_per_view;
  if (dsm) {
    out.dsm = AssembleTiledDsm(config, plan, *dsm);
    mark("DSM");
  } else {
    RemoveDsmFiles(config);
  }
  out.ortho = MakeOrthoOfRun(config, input, out.dsm, out.dsm.written ? TiledRunClouds(config, plan)
                                                                     : std::vector<OrthoCloud>{});
  if (out.ortho.written) mark("true ortho");
  return out;
}

}  // namespace sacfuse
