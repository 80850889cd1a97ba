#include "jobs/tiled_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "config/result_settings.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "jobs/resource_usage.h"
#include "jobs/tile_marker.h"
#include "jobs/tile_merge.h"
#include "jobs/tiled_sac.h"

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

std::string CacheDir(const JobConfig& config) {
  return config.fusion.superpixel_cache_dir.empty() ? (fs::path(config.output.dir) / "superpixels").string()
                                                    : config.fusion.superpixel_cache_dir;
}

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

// One tile into its own LAS file and done marker; throws whatever the tile throws.
TileFusionResult ComputeTile(const JobConfig& config, const ColmapWorkspace& workspace, const TilePlan& plan,
                             const PlannedTile& tile, const LasWriterOptions& las, const std::string& tiles_dir,
                             const std::string& hash) {
  const auto start = std::chrono::steady_clock::now();
  TileFusionResult fused;
  bool has_las = false;
  {
    LasWriter writer(TileLasPath(tiles_dir, tile.id), las);
    fused = FuseTile(workspace, plan, tile, config.fusion.sac, CacheDir(config), writer);
    if (writer.num_points() > 0) {  // an empty tile writes no LAS (the writer removes its temporary file)
      writer.Close();
      has_las = true;
    }
  }
  TileDoneMarker marker = DescribeTileLas(tiles_dir, tile.id, has_las);
  marker.config_hash = hash;
  marker.views = tile.views.size();
  marker.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  marker.peak_rss_mib = PeakRssMiB();
  WriteTileDoneMarker(tiles_dir, marker);
  return fused;
}

}  // namespace

std::string TilesDir(const JobConfig& config) { return (fs::path(config.output.dir) / "tiles").string(); }

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

TiledRunOutcome RunTiledSac(const JobConfig& config, const ColmapWorkspace& workspace, const TilePlan& plan,
                            const std::vector<std::string>& rerun_ids, LasWriterOptions las_options,
                            const std::string& fused_las_path, const SacProgress& progress) {
  if (config.fusion.sac.correspondence == "dense") {
    throw ConfigError("fusion.correspondence = dense: not supported by tiled runs yet");
  }
  ValidateSacOptions(config.fusion.sac);
  const std::string tiles_dir = TilesDir(config);
  fs::create_directories(tiles_dir);
  const size_t temps = RemoveTemporaryFiles(tiles_dir) + RemoveTemporaryFiles(config.output.dir) +
                       RemoveTemporaryFiles(CacheDir(config), /*recursive=*/true);
  if (temps > 0) spdlog::info("removed {} half-written files left by an interrupted run", temps);
  las_options.offset = SharedTileOffset(plan);
  const std::string settings = ResultSettingsText(config);
  const std::string hash = ResultSettingsHash(config);

  TiledRunOutcome out;
  const std::set<std::string> rerun(rerun_ids.begin(), rerun_ids.end());
  std::vector<const PlannedTile*> todo;
  std::vector<std::string> merge_order;  // LAS files of the tiles that have points, grid order
  for (const PlannedTile& tile : plan.tiles) {
    if (tile.views.empty()) continue;
    ++out.tiles_with_views;
    if (rerun.count(tile.id)) {
      spdlog::info("tile {}: rerun requested", tile.id);
      todo.push_back(&tile);
      continue;
    }
    const TileCheck check = VerifyTileDone(tiles_dir, tile.id, hash);
    if (check.done) {
      spdlog::info("tile {}: done, skipped", tile.id);
      ++out.tiles_skipped;
    } else {
      spdlog::debug("tile {}: to compute ({})", tile.id, check.reason);
      todo.push_back(&tile);
    }
  }
  RecordSettings(tiles_dir, settings, todo.size());
  WriteManifest(tiles_dir, plan, las_options, hash);

  if (!todo.empty()) {
    std::error_code ec;
    fs::remove(fused_las_path, ec);  // stale until the tiles are merged again
    const auto sp_start = std::chrono::steady_clock::now();
    out.block.superpixels_computed =
        EnsureTiledSuperpixels(workspace, plan, config.fusion.sac, CacheDir(config), progress);
    out.block.superpixel_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sp_start).count();
    spdlog::info("superpixels: {} computed, {} reused ({:.1f} s); {} of {} tiles to compute",
                 out.block.superpixels_computed, workspace.views().size() - out.block.superpixels_computed,
                 out.block.superpixel_seconds, todo.size(), out.tiles_with_views);
  }
  SacStats& total = out.block.stats;
  total.emitted_per_view.assign(workspace.views().size(), 0);
  for (size_t i = 0; i < todo.size(); ++i) {
    const PlannedTile& tile = *todo[i];
    ClearTileState(tiles_dir, tile.id);
    ++out.tiles_computed;
    try {
      const TileFusionResult r = ComputeTile(config, workspace, plan, tile, las_options, tiles_dir, hash);
      AddSacStats(r.stats, &total);
      for (size_t v = 0; v < tile.views.size(); ++v)
        total.emitted_per_view[tile.views[v].view] += r.stats.emitted_per_view[v];
      spdlog::info("tile {} ({}/{}): {} views, {} points in its core, {} left to neighbours", tile.id, i + 1,
                   todo.size(), tile.views.size(), r.points_in_core, r.points_outside_core);
    } catch (const std::exception& e) {
      spdlog::error("tile {}: failed: {}", tile.id, e.what());
      WriteTileFailedMarker(tiles_dir, tile.id, e.what());
      out.failed.emplace_back(tile.id, e.what());
    }
    if (progress) progress("tiles", i + 1, todo.size());
  }
  if (total.valid_nodes > 0) total.mean_correspondences /= static_cast<double>(total.valid_nodes);
  if (!out.failed.empty()) return out;

  for (const PlannedTile& tile : plan.tiles) {
    if (tile.views.empty()) continue;
    const auto marker = ReadTileDoneMarker(tiles_dir, tile.id);
    if (!marker) throw Error(TileDonePath(tiles_dir, tile.id) + ": done marker vanished before the merge");
    if (marker->points > 0) merge_order.push_back(TileLasPath(tiles_dir, tile.id));
  }
  const MergeResult merged = MergeTileLas(merge_order, fused_las_path, las_options, [&](size_t done, size_t n) {
    if (progress) progress("merge", done, n);
  });
  out.merged = true;
  out.merged_points = merged.points;
  out.points_per_view = merged.points_per_view;
  spdlog::info("merged {} tile files ({} points) into {}", merge_order.size(), merged.points, fused_las_path);
  return out;
}

}  // namespace sacfuse
