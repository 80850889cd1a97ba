#include "jobs/tile_queue.h"

#include <filesystem>
#include <functional>
#include <optional>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "core/error.h"
#include "jobs/auto_tiling.h"
#include "jobs/coregistered_block.h"
#include "jobs/dsm_product.h"
#include "jobs/las_options.h"
#include "jobs/open_input.h"
#include "jobs/run_state.h"
#include "jobs/thread_limit.h"
#include "jobs/tile_fusion.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

// Opens the workspace and resolves an automatic tile size into *resolved; throws ConfigError for untiled jobs.
// `before_coregistration` (may be empty) sees the resolved config before anything is written to DIR.
std::unique_ptr<DepthBlock> OpenTiledInput(const JobConfig& config, JobConfig* resolved,
                                           const std::function<void(const JobConfig&)>& before_coregistration = {}) {
  ValidateJobConfig(config);
  std::unique_ptr<DepthBlock> input = OpenNonEmptyInput(config.input, "fuse", config.crs);
  *resolved = ResolveTiling(config, *input);
  if (resolved->tiling.tile_size_m <= 0) {
    throw ConfigError("not a tiled run: tiling.tile_size_m = 0 and the whole block fits in resources.memory_gb, so "
                      "it runs untiled (`sacfuse run`); set tiling.tile_size_m > 0 to cut it into tiles");
  }
  if (before_coregistration) before_coregistration(*resolved);
  const ThreadLimit thread_limit(EffectiveThreads(*resolved));
  return WithCoregisteredPoses(*resolved, std::move(input));
}

}  // namespace

TilePlan PlanJob(const JobConfig& given, std::string* plan_path) {
  ValidateJobConfig(given);
  std::unique_ptr<DepthBlock> input = OpenNonEmptyInput(given.input, "plan", given.crs);
  const JobConfig config = ResolveTiling(given, *input);
  input = WithCoregisteredPoses(config, std::move(input));
  return SharedTilePlan(config, *input, IdentifyBlock(*input).views, plan_path);
}

TileWorkOutcome RunOneTile(const JobConfig& given, const std::string& id, const OutputWorkerLock& /*held*/) {
  RemoveTemporaryFilesOfGoneProcesses(given, nullptr);
  JobConfig config;
  // A writer of another job in DIR: refused before this worker writes anything (coregistration.json, plan.json).
  const auto check_settings = [](const JobConfig& resolved) {
    const std::optional<OutputWriter> writer = LiveOutputWriter(resolved);
    if (writer) CheckWorkerMatchesWriter(resolved, ResultSettingsHash(resolved), writer->inputs_digest);
  };
  const std::unique_ptr<DepthBlock> input = OpenTiledInput(given, &config, check_settings);
  const ThreadLimit thread_limit(EffectiveThreads(config));
  const BlockIdentity identity = IdentifyBlock(*input);
  CheckWorkerMatchesWriter(config, ResultSettingsHash(config), IdentitiesDigest(identity.views));
  const TilePlan plan = SharedTilePlan(config, *input, identity.views);
  const PlannedTile* tile = nullptr;
  for (const PlannedTile& t : plan.tiles) {
    if (t.id == id && !t.views.empty()) tile = &t;
  }
  if (tile == nullptr) {
    throw ConfigError("--id " + id + ": not a tile with views of this job (see `sacfuse plan CONFIG --list`)");
  }
  TileJob job{config, *input, plan, TileCloudOptions(config, plan), TilesDir(config), ResultSettingsHash(config),
              identity.views, /*caches_ready=*/false, {}};
  const std::optional<DsmGrid> dsm = DsmGridOf(config, *input, plan.grid.area());
  std::optional<DsmTileProduct> dsm_product;
  if (dsm) job.products.push_back(&dsm_product.emplace(*dsm));
  fs::create_directories(job.tiles_dir);
  const TileInputs inputs = TileInputsOf(*tile, input->views(), identity.views);
  if (VerifyTileDone(job.tiles_dir, id, job.hash, true, &inputs).done) return {};
  RecordTiledRunState(config, plan, job.cloud.las, 1);
  MethodTileFuser fuser(config, *input, plan, identity.views);
  return WorkOnTile(job, *tile, /*forced=*/false, nullptr, fuser);
}

MergeJobOutcome MergeJob(const JobConfig& given, OutputWriterLock& lock) {
  RemoveTemporaryFilesOfGoneProcesses(given, &lock);
  JobConfig config;
  const std::unique_ptr<DepthBlock> input = OpenTiledInput(given, &config);
  const ThreadLimit thread_limit(EffectiveThreads(config));  // resources.threads, as a run's merge
  const BlockIdentity identity = IdentifyBlock(*input);
  lock.Record(ResultSettingsHash(config), IdentitiesDigest(identity.views));
  const TilePlan plan = SharedTilePlan(config, *input, identity.views);
  MergeJobOutcome out;
  out.fused_las_path = FusedLasPath(config);
  out.missing = MissingTiles(config, *input, plan, identity.views);
  if (!out.missing.empty()) return out;
  out.merged = MergeTiledRun(config, *input, plan, identity.views, FusedCloudOptions(config, plan), out.fused_las_path);
  RemoveOtherFormatCloud(config);
  if (const std::optional<DsmGrid> dsm = DsmGridOf(config, *input, plan.grid.area())) {
    out.dsm = AssembleTiledDsm(config, plan, *dsm);
  } else {
    RemoveDsmFiles(config);
  }
  out.ortho = MakeOrthoOfRun(config, *input, out.dsm, out.dsm.written ? TiledRunClouds(config, plan)
                                                                      : std::vector<OrthoCloud>{});
  return out;
}

}  // namespace sacfuse
