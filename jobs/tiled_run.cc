#include "jobs/output_layout.h"
#include "jobs/tiled_run.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <atomic>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "config/result_settings.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "jobs/auto_tiling.h"
#include "jobs/fusion_methods.h"
#include "jobs/memory_admission.h"
#include "jobs/memory_model.h"
#include "jobs/method_memory.h"
#include "jobs/resource_usage.h"
#include "jobs/tile_claim.h"
#include "jobs/tile_marker.h"
#include "jobs/tile_merge.h"
#include "jobs/superpixel_cache.h"
#include "jobs/tile_queue.h"
#include "jobs/tile_worker.h"
#include "jobs/tile_fusion.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

constexpr double kOffsetSnapM = 1000.0;

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace


namespace {

void WriteManifest(const std::string& tiles_dir, const TilePlan& plan, const LasWriterOptions& las,
                   const std::string& hash) {
  const Eigen::Vector3d& o = *las.offset;
  const nlohmann::json j = {{"config_hash", hash},
                            {"tile_size_m", plan.options.tile_size_m},
                            {"grid", {plan.grid.num_x(), plan.grid.num_y()}},
                            {"scale_m", las.scale_m},
                            {"offset", {o.x(), o.y(), o.z()}},
                            {"tiles", TileIdsWithViews(plan)},
                            {"tiles_without_views", plan.tiles.size() - TileIdsWithViews(plan).size()}};
  WriteFileAtomically((fs::path(tiles_dir) / "manifest.json").string(), j.dump(2) + "\n");
}

// Logs what changed since the last run's settings and stores the current ones.
void RecordSettings(const std::string& tiles_dir, const std::string& settings, size_t tiles_to_compute) {
  const std::string path = (fs::path(tiles_dir) / "run_config.yaml").string();
  if (fs::exists(path)) {
    const std::vector<std::string> changed = ChangedResultSettings(ReadText(path), settings);
    if (!changed.empty()) {
      std::string keys;
      for (const auto& c : changed) keys += (keys.empty() ? "" : ", ") + c;
      spdlog::warn("config changed ({}) — recomputing {} tiles", keys, tiles_to_compute);
    }
  }
  WriteFileAtomically(path, settings);
}

}  // namespace

void RecordTiledRunState(const JobConfig& config, const TilePlan& plan, const LasWriterOptions& las,
                         size_t tiles_to_compute) {
  const std::string tiles_dir = TilesDir(config);
  fs::create_directories(tiles_dir);
  RecordSettings(tiles_dir, ResultSettingsText(config), tiles_to_compute);
  WriteManifest(tiles_dir, plan, las, ResultSettingsHash(config));
}

FusedViews ComputeTileFiles(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                            const PlannedTile& tile, const LasWriterOptions& las, const std::string& tiles_dir,
                            const std::string& hash, const TileInputs& inputs, ClusterTableCache* cluster_cache) {
  spdlog::info("computing tile {} (pid {})", tile.id, static_cast<long>(::getpid()));
  ClearTileState(tiles_dir, tile.id);
  const auto start = std::chrono::steady_clock::now();
  FusedViews fused;
  bool has_las = false;
  {
    LasWriter writer(TileLasPath(tiles_dir, tile.id), las);
    fused = FuseTile(input, plan, tile, WithTsdfMemoryLimit(config), SuperpixelCacheDir(config), writer, cluster_cache);
    if (writer.num_points() > 0) {  // an empty tile writes no LAS (the writer removes its temporary file)
      writer.Close();
      has_las = true;
    }
  }
  TileDoneMarker marker = DescribeTileLas(tiles_dir, tile.id, has_las);
  marker.config_hash = hash;
  marker.views = tile.views.size();
  marker.inputs = inputs;
  marker.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  marker.peak_rss_mib = PeakRssMiB();
  WriteTileDoneMarker(tiles_dir, marker);
  return fused;
}

void CheckTileFitsBudget(const PlannedTile& tile, const JobConfig& config) {
  const uint64_t pool = TileMemoryPoolBytes(MemoryBudgetBytes(config.resources.memory_gb));
  const uint64_t bytes = MethodTileBytes(tile, config.fusion);  // SAC: tile.memory_bytes
  if (bytes <= pool) return;
  throw Error(fmt::format("tile {}: out-of-memory guard: its {} views' windows need ~{:.2f} GiB, more than the "
                          "{:.2f} GiB that resources.memory_gb = {} leaves for tiles; use a smaller "
                          "tiling.tile_size_m (or 0 = sized from the budget) or raise resources.memory_gb",
                          tile.id, tile.views.size(), static_cast<double>(bytes) / kGiB,
                          static_cast<double>(pool) / kGiB, config.resources.memory_gb));
}


Eigen::Vector3d SharedTileOffset(const TilePlan& plan) {
  const auto snap = [](double v) { return std::floor(v / kOffsetSnapM) * kOffsetSnapM; };
  return {snap(plan.grid.area().min.x()), snap(plan.grid.area().min.y()), snap(plan.z_min_m)};
}

std::vector<std::string> TileIdsWithViews(const TilePlan& plan) {
  std::vector<std::string> ids;
  for (const PlannedTile& t : plan.tiles) {
    if (!t.views.empty()) ids.push_back(t.id);
  }
  return ids;
}

TiledRunOutcome RunTiledJob(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                            const std::vector<ViewIdentity>& identities,
                            const std::vector<std::string>& rerun_ids, LasWriterOptions las_options,
                            const std::string& fused_las_path, const SacProgress& progress) {
  const FusionNeeds needs = MakeFusionMethod(config.fusion)->needs();
  if (needs.consistency_graphs) {
    throw ConfigError("fusion.correspondence = dense: not supported by tiled runs yet");
  }
  const std::string tiles_dir = TilesDir(config);
  const double claim_timeout_s = config.tiling.claim_timeout_s;
  fs::create_directories(tiles_dir);
  if (!AnyLiveTileClaim(tiles_dir, claim_timeout_s)) {
    const size_t claims = RemoveStaleTileClaims(tiles_dir, claim_timeout_s);
    if (claims > 0) spdlog::info("removed {} stale tile claims left by killed workers", claims);
  }
  las_options.offset = SharedTileOffset(plan);  // the merged cloud's: output.format
  LasWriterOptions tile_las = las_options;       // tiles stay uncompressed LAS (intermediate files)
  tile_las.compressed = false;
  const std::string hash = ResultSettingsHash(config);

  TiledRunOutcome out;
  const std::set<std::string> rerun(rerun_ids.begin(), rerun_ids.end());
  std::vector<const PlannedTile*> todo;
  std::set<std::string> changed_views;  // "view 12 (a.jpg): depth map changed (...)", from the tiles' markers
  std::vector<std::string> rerun_for_inputs;
  for (const PlannedTile& tile : plan.tiles) {
    if (tile.views.empty()) continue;
    ++out.tiles_with_views;
    if (rerun.count(tile.id)) {
      spdlog::info("tile {}: rerun requested", tile.id);
      todo.push_back(&tile);
      continue;
    }
    const TileInputs inputs = TileInputsOf(tile, input.views(), identities);
    const TileCheck check = VerifyTileDone(tiles_dir, tile.id, hash, true, &inputs);
    if (check.done) {
      spdlog::info("tile {}: done, skipped", tile.id);
      ++out.tiles_skipped;
    } else if (!check.input_changes.empty()) {
      spdlog::info("tile {}: recomputed: {}", tile.id, check.reason);
      changed_views.insert(check.input_changes.begin(), check.input_changes.end());
      rerun_for_inputs.push_back(tile.id);
      todo.push_back(&tile);
    } else {
      spdlog::debug("tile {}: to compute ({})", tile.id, check.reason);
      todo.push_back(&tile);
    }
  }
  if (!rerun_for_inputs.empty()) {
    for (const std::string& change : changed_views) spdlog::info("input changed: {}", change);
    std::string ids;
    for (const std::string& id : rerun_for_inputs) ids += (ids.empty() ? "" : ", ") + id;
    spdlog::info("{} tiles rerun because their inputs changed: {}", rerun_for_inputs.size(), ids);
  }
  out.tiles_rerun_for_inputs = rerun_for_inputs;
  RecordTiledRunState(config, plan, tile_las, todo.size());

  if (!todo.empty()) {
    const auto sp_start = std::chrono::steady_clock::now();
    out.superpixels_computed = EnsureTiledSuperpixels(input, plan, config.fusion.sac, SuperpixelCacheDir(config),
                                                      identities, progress, nullptr, needs.superpixels);
    out.superpixel_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sp_start).count();
    if (needs.superpixels) {
      spdlog::info("superpixels: {} computed, {} reused ({:.1f} s); {} of {} tiles to compute",
                   out.superpixels_computed, input.views().size() - out.superpixels_computed,
                   out.superpixel_seconds, todo.size(), out.tiles_with_views);
    } else {
      spdlog::info("colour caches checked ({:.1f} s; no superpixels for {}); {} of {} tiles to compute",
                   out.superpixel_seconds, config.fusion.method, todo.size(), out.tiles_with_views);
    }
  }
  const size_t num_views = input.views().size();
  out.stats.input_per_view.assign(num_views, 0);
  out.stats.emitted_per_view.assign(num_views, 0);
  ClusterTableCache cluster_cache(ClusterCacheBudgetBytes(MemoryBudgetBytes(config.resources.memory_gb)));
  MemoryAdmission admission(TileMemoryPoolBytes(MemoryBudgetBytes(config.resources.memory_gb)));
  std::mutex mutex;  // guards out and progress across tile workers
  const TileJob job{config, input, plan, tile_las, tiles_dir, hash, identities, /*caches_ready=*/true};
  // Works on one tile; false when another live worker holds it.
  const auto attempt = [&](const PlannedTile& tile, bool forced) {
    const TileWorkOutcome r = WorkOnTile(job, tile, forced, &admission, &cluster_cache);
    std::lock_guard<std::mutex> lock(mutex);
    if (r.result == TileWork::kComputed || r.result == TileWork::kFailed) ++out.tiles_computed;
    if (r.result == TileWork::kComputed) out.stats.Add(r.fused.stats, r.fused.view_ids, num_views);
    if (r.result == TileWork::kFailed) out.failed.emplace_back(tile.id, r.detail);
    return r.result != TileWork::kHeldElsewhere;
  };
  std::vector<const PlannedTile*> held;  // by other live workers
  const size_t workers = std::min<size_t>(static_cast<size_t>(EffectiveThreads(config)), todo.size());
  if (workers > 1) spdlog::info("{} tiles on {} worker threads within {:.2f} GiB for tiles", todo.size(), workers,
                                static_cast<double>(admission.pool()) / kGiB);
  std::atomic<size_t> next{0};
  size_t finished = 0;
  std::exception_ptr worker_error;  // claim I/O errors end the run after the workers stop
  const auto work = [&] {
    try {
      for (size_t i = next++; i < todo.size(); i = next++) {
        const bool computed_or_done = attempt(*todo[i], rerun.count(todo[i]->id) > 0);
        std::lock_guard<std::mutex> lock(mutex);
        if (!computed_or_done) held.push_back(todo[i]);
        ++finished;
        if (progress) progress("tiles", finished, todo.size());
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!worker_error) worker_error = std::current_exception();
      next = todo.size();  // the other workers stop after their current tile
    }
  };
  const auto tiles_start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (size_t w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (worker_error) std::rethrow_exception(worker_error);
  out.tiles_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tiles_start).count();
  // Failures and held tiles in id order whatever the thread timing.
  std::sort(out.failed.begin(), out.failed.end());
  std::sort(held.begin(), held.end(), [](const PlannedTile* a, const PlannedTile* b) { return a->id < b->id; });
  if (!held.empty()) {
    std::string ids;
    for (const PlannedTile* t : held) ids += (ids.empty() ? "" : ",") + t->id;
    spdlog::info("waiting for {} tiles held by other workers ({}), polling every second", held.size(), ids);
  }
  while (!held.empty()) {
    std::this_thread::sleep_for(std::chrono::seconds(1));
    std::vector<const PlannedTile*> still;
    for (const PlannedTile* t : held) {
      const TileInputs inputs = TileInputsOf(*t, input.views(), identities);
      if (VerifyTileDone(tiles_dir, t->id, hash, true, &inputs).done) continue;
      // Not done and no live claim: its worker died or failed, so it is computed here.
      if (TileClaimIsLive(tiles_dir, t->id, claim_timeout_s) || !attempt(*t, false)) still.push_back(t);
    }
    held.swap(still);
  }
  if (!out.failed.empty()) return out;

  const auto merge_start = std::chrono::steady_clock::now();
  const MergeResult merged = MergeTiledRun(config, plan, las_options, fused_las_path, progress);
  out.merge_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - merge_start).count();
  out.merged = true;
  out.merged_points = merged.points;
  out.points_per_view = merged.points_per_view;
  return out;
}

}  // namespace sacfuse
