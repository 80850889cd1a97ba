#include "jobs/auto_tiling.h"

#include <algorithm>
#include <optional>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>

#include "config/output_layout.h"
#include "core/error.h"
#include "tiles/memory_model.h"
#include "jobs/method_memory.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_plan.h"
#include "core/cell_window.h"

namespace sacfuse {
namespace {

// Tile edges tried from the largest down, metres.
constexpr double kCandidateTileSizesM[] = {2000, 1500, 1000, 800, 600, 500, 400, 300, 250, 200, 160,
                                           128,  100,  80,   64,  50,  40,  32,  25,  20,  16,  12, 10};

double GiB(uint64_t bytes) { return static_cast<double>(bytes) / kGiB; }

// The tile size recorded by a tiled run already started in this output folder (0 = none).
double TileSizeOfRunInProgress(const JobConfig& config) {
  try {
    const std::optional<TileManifest> manifest = TileManifest::Read(TilesDir(config));
    return manifest ? manifest->tile_size_m : 0.0;
  } catch (const std::exception&) {
    return 0.0;
  }
}

uint64_t LargestTileBytes(const TilePlan& plan, const FusionOptions& fusion, size_t* tiles_with_views) {
  uint64_t largest = 0;
  *tiles_with_views = 0;
  for (const PlannedTile& t : plan.tiles) {
    if (t.views.empty()) continue;
    ++*tiles_with_views;
    largest = std::max(largest, MethodTileBytes(t, fusion));  // SAC: t.memory_bytes
  }
  return largest;
}

}  // namespace

int EffectiveThreads(const JobConfig& config) {
  if (config.resources.threads > 0) return config.resources.threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

TilingDecision DecideTiling(const JobConfig& config, const DepthBlock& input) {
  TilingDecision d;
  d.budget_bytes = MemoryBudgetBytes(config.resources.memory_gb);
  const BlockPixels pixels = MeasureBlockPixels(input);
  d.untiled_bytes =
      UntiledSacBytes(pixels) + MethodExtraBytesPerDepthPixel(config.fusion) * pixels.total_depth_pixels();
  const int threads = EffectiveThreads(config);
  const uint64_t pool = TileMemoryPoolBytes(d.budget_bytes);
  const uint64_t superpixel_bytes = SuperpixelPassBytes(pixels);
  if (config.fusion.method == FusionMethodKind::kSac && superpixel_bytes > d.budget_bytes) {
    spdlog::warn("the superpixel pass needs ~{} for the largest view, more than resources.memory_gb = {} ({})",
                 ByteSizeText(superpixel_bytes), config.resources.memory_gb, ByteSizeText(d.budget_bytes));
  }
  // Tiled: the superpixel pass runs alone before the tiles; untiled: beside the whole block (set below).
  d.views_in_flight = SuperpixelViewsInFlight(pixels, d.budget_bytes, static_cast<size_t>(threads), superpixel_bytes);
  if (config.tiling.tile_size_m > 0) {
    d.tiled = true;
    d.tile_size_m = config.tiling.tile_size_m;
    d.reason = "tiling.tile_size_m = " + std::to_string(config.tiling.tile_size_m) + " (given)";
    return d;
  }
  d.automatic = true;
  if (d.untiled_bytes <= d.budget_bytes) {
    d.views_in_flight = SuperpixelViewsInFlight(pixels, d.budget_bytes, static_cast<size_t>(threads), d.untiled_bytes);
    d.reason = "untiled: the whole block needs ~" + fmt::format("{:.2f}", GiB(d.untiled_bytes)) +
               " GiB of the " + fmt::format("{:.2f}", GiB(d.budget_bytes)) + " GiB budget";
    return d;
  }
  if (config.fusion.method == FusionMethodKind::kSac && config.fusion.sac.correspondence == "dense") {
    throw ConfigError("fusion.correspondence = dense runs untiled only, but this block needs ~" +
                      fmt::format("{:.2f}", GiB(d.untiled_bytes)) + " GiB > resources.memory_gb = " +
                      fmt::format("{}", config.resources.memory_gb) +
                      "; raise the budget or use reprojection correspondences");
  }
  const double in_progress = TileSizeOfRunInProgress(config);
  std::vector<double> candidates;
  if (in_progress > 0) candidates.push_back(in_progress);
  const bool fixed_dsm_cell = DsmWanted(config) && config.output.dsm_cell_m > 0;
  for (const double s : kCandidateTileSizesM) {
    // Tiles must hold whole DSM cells (an automatic cell is chosen to divide the tile size instead).
    if (fixed_dsm_cell && !IsWholeNumberOfCells(s, config.output.dsm_cell_m)) continue;
    if (s >= 2.0 * config.tiling.halo_m) candidates.push_back(s);
  }
  uint64_t smallest_bytes = 0;
  double smallest_size = 0;
  // First the largest tiles of which `threads` fit at once; failing that, the largest that fit one at a time.
  for (const int wanted : {threads, 1}) {
    for (const double size : candidates) {
      TilingOptions options = config.tiling;
      options.tile_size_m = size;
      std::optional<TilePlan> plan;
      try {
        plan.emplace(BuildTilePlan(input, options));
      } catch (const ConfigError&) {
        continue;  // a candidate the grid refuses (below kMinTileSizeGsd GSD, or over kMaxTiles tiles): not for us
      }
      size_t tiles = 0;
      const uint64_t largest = LargestTileBytes(*plan, config.fusion, &tiles);
      const int parallel = static_cast<int>(std::min<size_t>(static_cast<size_t>(wanted), std::max<size_t>(tiles, 1)));
      smallest_bytes = largest;
      smallest_size = size;
      if (size != in_progress && largest * static_cast<uint64_t>(parallel) > pool) continue;
      d.tiled = true;
      d.tile_size_m = size;
      d.max_tile_bytes = largest;
      d.parallel_tiles = static_cast<int>(std::clamp<uint64_t>(pool / std::max<uint64_t>(largest, 1), 1, threads));
      d.reason = size == in_progress
                     ? fmt::format("{} m tiles: the tile size of the run in progress in {}", size, config.output.dir)
                     : fmt::format("{} m tiles: untiled would need ~{:.2f} GiB; the largest tile ~{:.3f} GiB, {} at "
                                   "once in the {:.2f} GiB budget",
                                   size, GiB(d.untiled_bytes), GiB(largest), d.parallel_tiles, GiB(d.budget_bytes));
      return d;
    }
  }
  throw ConfigError(fmt::format("resources.memory_gb = {}: too small for this block: even {} m tiles need ~{} "
                                "each (plus {} reserved for the process and shared tables)",
                                config.resources.memory_gb, smallest_size, ByteSizeText(smallest_bytes),
                                ByteSizeText(d.budget_bytes - std::min(d.budget_bytes, pool))));
}

JobConfig ResolveTiling(const JobConfig& config, const DepthBlock& input, TilingDecision* decision) {
  const TilingDecision d = DecideTiling(config, input);
  spdlog::info("tiling: {}", d.reason);
  JobConfig out = config;
  out.tiling.tile_size_m = d.tiled ? d.tile_size_m : 0.0;
  if (decision != nullptr) *decision = d;
  return out;
}

}  // namespace sacfuse
