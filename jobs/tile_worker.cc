#include "jobs/tile_worker.h"

#include <optional>

#include <spdlog/spdlog.h>

#include "jobs/fusion_methods.h"
#include "jobs/method_memory.h"
#include "jobs/superpixel_cache.h"
#include "jobs/tile_claim.h"
#include "jobs/tile_fusion.h"
#include "jobs/tile_marker.h"
#include "jobs/tiled_run.h"

namespace sacfuse {

TileWorkOutcome WorkOnTile(const TileJob& job, const PlannedTile& tile, bool forced, MemoryAdmission* admission,
                           ClusterTableCache* cluster_cache) {
  TileWorkOutcome out;
  const double claim_timeout_s = job.config.tiling.claim_timeout_s;
  const ClaimAttempt claim = TryClaimTile(job.tiles_dir, tile.id, claim_timeout_s);
  if (!claim.claimed) {
    spdlog::info("tile {}: claimed by {}, left to it", tile.id, claim.holder);
    out.result = TileWork::kHeldElsewhere;
    out.detail = claim.holder;
    return out;
  }
  TileClaimGuard guard(job.tiles_dir, tile.id, claim.token);
  if (claim.took_over) spdlog::warn("tile {}: took over a stale claim", tile.id);
  const TileInputs inputs = TileInputsOf(tile, job.input.views(), job.identities);
  if (!forced && VerifyTileDone(job.tiles_dir, tile.id, job.hash, true, &inputs).done) {
    spdlog::info("tile {}: done by another worker", tile.id);
    return out;
  }
  try {
    if (!job.caches_ready) {
      const bool superpixels = MakeFusionMethod(job.config.fusion)->needs().superpixels;
      EnsureTiledSuperpixels(job.input, job.plan, job.config.fusion.sac, SuperpixelCacheDir(job.config),
                             job.identities, {}, &tile, superpixels);
    }
    CheckTileFitsBudget(tile, job.config);
    std::optional<MemoryReservation> reservation;
    if (admission != nullptr) reservation.emplace(*admission, MethodTileBytes(tile, job.config.fusion));
    out.fused =
        ComputeTileFiles(job.config, job.input, job.plan, tile, job.las, job.tiles_dir, job.hash, inputs,
                         cluster_cache);
    reservation.reset();
    out.result = TileWork::kComputed;
    spdlog::info("tile {}: {} views, {} points in its core, {} left to neighbours", tile.id, tile.views.size(),
                 out.fused.points_written, out.fused.points_not_owned);
  } catch (const std::exception& e) {
    spdlog::error("tile {}: failed: {}", tile.id, e.what());
    WriteTileFailedMarker(job.tiles_dir, tile.id, e.what());
    out.result = TileWork::kFailed;
    out.detail = e.what();
  }
  return out;
}

}  // namespace sacfuse
