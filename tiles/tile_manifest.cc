#include "tiles/tile_manifest.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/json_text.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

constexpr double kOffsetSnapM = 1000.0;

// Logs what changed since the last run's settings and stores the current ones.
void RecordSettings(const std::string& tiles_dir, const std::string& settings, size_t tiles_to_compute) {
  const std::string path = (fs::path(tiles_dir) / "run_config.yaml").string();
  if (fs::exists(path)) {
    const std::vector<std::string> changed = ChangedResultSettings(ReadSmallFile(path), settings);
    if (!changed.empty()) {
      std::string keys;
      for (const auto& c : changed) keys += (keys.empty() ? "" : ", ") + c;
      spdlog::warn("config changed ({}) — recomputing {} tiles", keys, tiles_to_compute);
    }
  }
  WriteFileAtomically(path, settings);
}

}  // namespace

TileManifest TileManifest::Of(const TilePlan& plan, const LasWriterOptions& las, const std::string& hash) {
  TileManifest m;
  m.config_hash = hash;
  m.tile_size_m = plan.options.tile_size_m;
  m.grid_x = plan.grid.num_x();
  m.grid_y = plan.grid.num_y();
  m.scale_m = las.scale_m;
  m.offset = *las.offset;
  m.tiles = TileIdsWithViews(plan);
  m.tiles_without_views = plan.tiles.size() - m.tiles.size();
  return m;
}

std::string TileManifest::Path(const std::string& tiles_dir) {
  return (fs::path(tiles_dir) / "manifest.json").string();
}

std::optional<TileManifest> TileManifest::Read(const std::string& tiles_dir) {
  const std::string path = Path(tiles_dir);
  std::ifstream in(path);
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    TileManifest m;
    m.config_hash = j.value("config_hash", "");
    m.tile_size_m = j.value("tile_size_m", 0.0);
    if (j.contains("grid")) {
      const std::vector<int> grid = j.at("grid").get<std::vector<int>>();
      m.grid_x = grid.at(0);
      m.grid_y = grid.at(1);
    }
    m.scale_m = j.value("scale_m", 0.0);
    if (j.contains("offset")) {
      const std::vector<double> offset = j.at("offset").get<std::vector<double>>();
      m.offset = {offset.at(0), offset.at(1), offset.at(2)};
    }
    m.tiles = j.at("tiles").get<std::vector<std::string>>();
    m.tiles_without_views = j.value("tiles_without_views", size_t{0});
    return m;
  } catch (const std::exception& e) {
    throw Error(path + " unreadable (" + e.what() + ")");
  }
}

void TileManifest::Write(const std::string& tiles_dir) const {
  const nlohmann::json j = {{"config_hash", config_hash},
                            {"tile_size_m", tile_size_m},
                            {"grid", {grid_x, grid_y}},
                            {"scale_m", scale_m},
                            {"offset", {offset.x(), offset.y(), offset.z()}},
                            {"tiles", tiles},
                            {"tiles_without_views", tiles_without_views}};
  WriteFileAtomically(Path(tiles_dir), JsonText(j, 2) + "\n");
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

void RecordTiledRunState(const JobConfig& config, const TilePlan& plan, const LasWriterOptions& las,
                         size_t tiles_to_compute) {
  const std::string tiles_dir = TilesDir(config);
  fs::create_directories(tiles_dir);
  RecordSettings(tiles_dir, ResultSettingsText(config), tiles_to_compute);
  TileManifest::Of(plan, las, ResultSettingsHash(config)).Write(tiles_dir);
}

}  // namespace sacfuse
