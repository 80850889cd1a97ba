#include "tiles/tile_worker.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <optional>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "io/resource_usage.h"
#include "io/test_pause.h"
#include "tiles/memory_model.h"
#include "tiles/tile_claim.h"

namespace sacfuse {

TileFused ComputeTileFiles(const TileJob& job, const PlannedTile& tile, const TileInputs& inputs, TileFuser& fuser) {
  spdlog::info("computing tile {} (pid {})", tile.id, static_cast<long>(::getpid()));
  ClearTileState(job.tiles_dir, tile.id, ProductSuffixes(job));
  const auto start = std::chrono::steady_clock::now();
  TileFused fused;
  const std::string file = TileCloudFileName(tile.id, job.cloud.copc.has_value());
  std::string written;
  {
    const std::unique_ptr<PointCloudWriter> writer =
        OpenPointCloudWriter((std::filesystem::path(job.tiles_dir) / file).string(), job.cloud);
    fused = fuser.Fuse(tile, *writer);
    if (writer->num_points() > 0) {  // an empty tile writes no file (the writer removes its temporary file)
      writer->Close();
      written = file;
    }
  }
  TileDoneMarker marker = DescribeTileFile(job.tiles_dir, tile.id, written);
  const std::string cloud_path = written.empty() ? "" : (std::filesystem::path(job.tiles_dir) / written).string();
  for (const TileProduct* product : job.products) {
    for (const std::string& suffix : product->Make(tile, cloud_path, job.tiles_dir)) {
      marker.products.push_back(DescribeTileProduct(job.tiles_dir, tile.id, suffix));
    }
  }
  marker.config_hash = job.hash;
  marker.views = tile.views.size();
  for (uint32_t v = 0; v < fused.points_per_view.size(); ++v) {
    if (fused.points_per_view[v] > 0) marker.points_per_view.emplace_back(v, fused.points_per_view[v]);
  }
  marker.inputs = inputs;
  marker.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  marker.peak_rss_mib = PeakRssMiB();
  WriteTileDoneMarker(job.tiles_dir, marker);
  return fused;
}

std::vector<std::string> ProductSuffixes(const TileJob& job) {
  std::vector<std::string> suffixes;
  for (const TileProduct* product : job.products) {
    for (const std::string& s : product->suffixes()) suffixes.push_back(s);
  }
  return suffixes;
}

void CheckTileFitsBudget(const PlannedTile& tile, uint64_t bytes, const JobConfig& config) {
  const uint64_t budget = MemoryBudgetBytes(config.resources.memory_gb);
  const uint64_t pool = TileMemoryPoolBytes(budget);
  if (bytes <= pool) return;
  const std::string left = pool > 0 ? "the " + ByteSizeText(pool) : "nothing";
  throw Error(fmt::format("tile {}: out-of-memory guard: its {} views' windows need ~{}, more than {} that "
                          "resources.memory_gb = {} ({}) leaves for tiles after {} for the process and {} for "
                          "shared superpixel cluster tables; use a smaller tiling.tile_size_m (or 0 = sized from "
                          "the budget) or raise resources.memory_gb",
                          tile.id, tile.views.size(), ByteSizeText(bytes), left, config.resources.memory_gb,
                          ByteSizeText(budget), ByteSizeText(kProcessBaseBytes),
                          ByteSizeText(ClusterCacheBudgetBytes(budget))));
}

TileWorkOutcome WorkOnTile(const TileJob& job, const PlannedTile& tile, bool forced, MemoryAdmission* admission,
                           TileFuser& fuser) {
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
  PauseAtTestPoint("tile:claimed");
  if (claim.took_over) spdlog::warn("tile {}: took over a stale claim", tile.id);
  const TileInputs inputs = TileInputsOf(tile, job.input.views(), job.identities);
  if (!forced && VerifyTileDone(job.tiles_dir, tile.id, job.hash, true, &inputs).done) {
    spdlog::info("tile {}: done by another worker", tile.id);
    return out;
  }
  try {
    if (!job.caches_ready) fuser.PrepareTile(tile);
    const uint64_t bytes = fuser.TileBytes(tile);
    CheckTileFitsBudget(tile, bytes, job.config);
    std::optional<MemoryReservation> reservation;
    if (admission != nullptr) reservation.emplace(*admission, bytes);
    out.fused = ComputeTileFiles(job, tile, inputs, fuser);
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
