#include "tiles/tile_scheduler.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "tiles/memory_admission.h"
#include "tiles/memory_model.h"
#include "tiles/tile_claim.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace {

std::string JoinIds(const std::vector<std::string>& ids, const char* separator) {
  std::string text;
  for (const std::string& id : ids) text += (text.empty() ? "" : separator) + id;
  return text;
}

bool IsDone(const TileJob& job, const PlannedTile& tile) {
  const TileInputs inputs = TileInputsOf(tile, job.input.views(), job.identities);
  return VerifyTileDone(job.tiles_dir, tile.id, job.hash, true, &inputs).done;
}

// Polls every second until every tile in `held` is done; one whose claim is no longer live (its worker died or
// failed) is computed here through `attempt` (false: held by another worker again).
template <typename Attempt>
void WaitForHeldTiles(const TileJob& job, std::vector<const PlannedTile*> held, const Attempt& attempt) {
  std::sort(held.begin(), held.end(), [](const PlannedTile* a, const PlannedTile* b) { return a->id < b->id; });
  if (!held.empty()) {
    std::vector<std::string> ids;
    for (const PlannedTile* t : held) ids.push_back(t->id);
    spdlog::info("waiting for {} tiles held by other workers ({}), polling every second", held.size(),
                 JoinIds(ids, ","));
  }
  while (!held.empty()) {
    std::this_thread::sleep_for(std::chrono::seconds(1));
    std::vector<const PlannedTile*> still;
    for (const PlannedTile* t : held) {
      if (IsDone(job, *t)) continue;
      // Not done and no live claim: its worker died or failed, so it is computed here.
      if (TileClaimIsLive(job.tiles_dir, t->id, job.config.tiling.claim_timeout_s) || !attempt(*t, false)) {
        still.push_back(t);
      }
    }
    held.swap(still);
  }
}

}  // namespace

TileWorkList ListTileWork(const TileJob& job, const std::vector<std::string>& rerun_ids) {
  const double claim_timeout_s = job.config.tiling.claim_timeout_s;
  std::filesystem::create_directories(job.tiles_dir);
  if (!AnyLiveTileClaim(job.tiles_dir, claim_timeout_s)) {
    const size_t claims = RemoveStaleTileClaims(job.tiles_dir, claim_timeout_s);
    if (claims > 0) spdlog::info("removed {} stale tile claims left by killed workers", claims);
  }
  TileWorkList out;
  const std::set<std::string> rerun(rerun_ids.begin(), rerun_ids.end());
  std::set<std::string> changed_views;  // "view 12 (a.jpg): depth map changed (...)", from the tiles' markers
  for (const PlannedTile& tile : job.plan.tiles) {
    if (tile.views.empty()) continue;
    ++out.tiles_with_views;
    if (rerun.count(tile.id)) {
      spdlog::info("tile {}: rerun requested", tile.id);
      out.todo.push_back(&tile);
      out.forced.push_back(tile.id);
      continue;
    }
    const TileInputs inputs = TileInputsOf(tile, job.input.views(), job.identities);
    const TileCheck check = VerifyTileDone(job.tiles_dir, tile.id, job.hash, true, &inputs);
    if (check.done) {
      spdlog::info("tile {}: done, skipped", tile.id);
      ++out.tiles_skipped;
    } else if (!check.input_changes.empty()) {
      spdlog::info("tile {}: recomputed: {}", tile.id, check.reason);
      changed_views.insert(check.input_changes.begin(), check.input_changes.end());
      out.rerun_for_inputs.push_back(tile.id);
      out.todo.push_back(&tile);
    } else {
      spdlog::debug("tile {}: to compute ({})", tile.id, check.reason);
      out.todo.push_back(&tile);
    }
  }
  if (!out.rerun_for_inputs.empty()) {
    for (const std::string& change : changed_views) spdlog::info("input changed: {}", change);
    spdlog::info("{} tiles rerun because their inputs changed: {}", out.rerun_for_inputs.size(),
                 JoinIds(out.rerun_for_inputs, ", "));
  }
  return out;
}

TileStageOutcome RunTileWork(const TileJob& job, const TileWorkList& work, int threads, TileFuser& fuser,
                             const StageProgress& progress) {
  TileStageOutcome out;
  const std::vector<const PlannedTile*>& todo = work.todo;
  const std::set<std::string> forced(work.forced.begin(), work.forced.end());
  const size_t num_views = job.input.views().size();
  out.stats.input_per_view.assign(num_views, 0);
  out.stats.emitted_per_view.assign(num_views, 0);
  MemoryAdmission admission(TileMemoryPoolBytes(MemoryBudgetBytes(job.config.resources.memory_gb)));
  std::mutex mutex;  // guards out, held and progress across tile workers
  // Works on one tile; false when another live worker holds it. Isolated: a worker waiting inside the tile's own
  // parallel loops never picks up another tile's task (which could wait for this tile's memory reservation).
  const auto attempt = [&](const PlannedTile& tile, bool forced_tile) {
    TileWorkOutcome r;
    tbb::this_task_arena::isolate([&] { r = WorkOnTile(job, tile, forced_tile, &admission, fuser); });
    std::lock_guard<std::mutex> lock(mutex);
    if (r.result == TileWork::kComputed || r.result == TileWork::kFailed) ++out.tiles_computed;
    if (r.result == TileWork::kComputed) out.stats.Add(r.fused.stats, r.fused.view_ids, num_views);
    if (r.result == TileWork::kFailed) out.failed.emplace_back(tile.id, r.detail);
    return r.result != TileWork::kHeldElsewhere;
  };
  std::vector<const PlannedTile*> held;  // by other live workers
  const size_t workers = std::min<size_t>(static_cast<size_t>(std::max(threads, 1)), todo.size());
  if (workers > 1) spdlog::info("{} tiles on {} worker threads within {:.2f} GiB for tiles", todo.size(), workers,
                                static_cast<double>(admission.pool()) / kGiB);
  std::atomic<size_t> next{0};
  size_t finished = 0;
  std::exception_ptr worker_error;  // claim I/O errors end the run after the workers stop
  // One worker: takes the next tile in grid order until none is left.
  const auto worker = [&] {
    try {
      for (size_t i = next++; i < todo.size(); i = next++) {
        const bool computed_or_done = attempt(*todo[i], forced.count(todo[i]->id) > 0);
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
  const auto start = std::chrono::steady_clock::now();
  if (workers > 0) {
    tbb::task_arena arena(static_cast<int>(workers));  // this thread and workers - 1 TBB workers
    arena.execute([&] {
      tbb::task_group group;
      for (size_t w = 0; w < workers; ++w) group.run(worker);
      group.wait();
    });
  }
  if (worker_error) std::rethrow_exception(worker_error);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Failures in id order whatever the thread timing.
  std::sort(out.failed.begin(), out.failed.end());
  WaitForHeldTiles(job, held, attempt);
  return out;
}

}  // namespace sacfuse
