#include "tiles/tile_plan.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "config/version.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_warnings.h"
#include "tiles/memory_model.h"
#include "io/json_text.h"

namespace sacfuse {
namespace {

double Percentile(std::vector<double>& values, double q) {
  const size_t k = static_cast<size_t>(std::floor(q * (values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

nlohmann::json BoxJson(const Box2d& b) { return {b.min.x(), b.min.y(), b.max.x(), b.max.y()}; }


}  // namespace

void BlockHeightRange(const DepthBlock& input, const TilingOptions& options, double* z_min_m, double* z_max_m,
                      std::string* source) {
  std::vector<double> z = input.SceneHeights();
  if (z.empty()) {
    *z_min_m = options.z_min_m;
    *z_max_m = options.z_max_m;
    *source = "config";
    WarnAboutInput(input.source(), fmt::format("no scene heights in the input (looked for: {}): the block's height range is "
                                               "tiling.z_min_m .. z_max_m = [{}, {}] m from the config; footprints "
                                               "and tiles hold only what lies in it",
                                               input.SceneHeightsSource(), options.z_min_m, options.z_max_m));
    return;
  }
  *z_min_m = Percentile(z, 0.02) - kSparseHeightPaddingM;
  *z_max_m = Percentile(z, 0.98) + kSparseHeightPaddingM;
  *source = input.SceneHeightsSource();
}

TilePlan BuildTilePlan(const DepthBlock& input, const TilingOptions& options) {
  ValidateTilingOptions(options);
  double z_min = 0, z_max = 0;
  std::string z_source;
  BlockHeightRange(input, options, &z_min, &z_max, &z_source);
  const auto& views = input.views();
  Box2d area;
  for (const View& view : views) area.Extend(FootprintBounds(view, z_min, z_max));
  if (area.IsEmpty()) {
    throw InputError(input.source(), "no view's footprint meets the height range [" + std::to_string(z_min) + ", " +
                                          std::to_string(z_max) + "] m; cannot plan tiles");
  }
  TilePlan plan(TileGrid(area, options.tile_size_m, options.halo_m, BlockGsdAtHeight(views, 0.5 * (z_min + z_max))));
  plan.options = options;
  plan.z_min_m = z_min;
  plan.z_max_m = z_max;
  plan.z_source = z_source;
  plan.depth_sizes.resize(views.size());
  for (size_t v = 0; v < views.size(); ++v) {
    plan.depth_sizes[v] = input.DepthSize(views[v]);
  }
  for (const TileIndex& t : plan.grid.Tiles()) {
    PlannedTile tile;
    tile.index = t;
    tile.id = TileGrid::Id(t);
    tile.core = plan.grid.CoreBounds(t);
    tile.halo = plan.grid.HaloBounds(t);
    for (size_t v = 0; v < views.size(); ++v) {
      const auto window = ViewWindowForBox(views[v], plan.depth_sizes[v].width, plan.depth_sizes[v].height,
                                           tile.halo, z_min, z_max, options.window_margin_px);
      if (!window) continue;
      tile.views.push_back({static_cast<uint32_t>(v), *window});
      tile.window_pixels += window->num_pixels();
    }
    tile.memory_bytes = TileBytes(tile.window_pixels);
    plan.tiles.push_back(std::move(tile));
  }
  return plan;
}

std::string TilePlanJson(const TilePlan& plan, const DepthBlock& input, const std::string& config_hash,
                         const std::string& inputs_hash) {
  nlohmann::json tiles = nlohmann::json::array();
  for (const PlannedTile& t : plan.tiles) {
    nlohmann::json views = nlohmann::json::array();
    for (const TileViewWindow& w : t.views) {
      views.push_back({{"view", w.view},
                       {"name", input.views()[w.view].name},
                       {"window", {{"row_begin", w.window.row_begin},
                                   {"row_end", w.window.row_end},
                                   {"col_begin", w.window.col_begin},
                                   {"col_end", w.window.col_end}}}});
    }
    tiles.push_back({{"id", t.id},
                     {"core", BoxJson(t.core)},
                     {"halo", BoxJson(t.halo)},
                     {"views", views},
                     {"window_pixels", t.window_pixels},
                     {"memory_bytes", t.memory_bytes}});
  }
  const Box2d& area = plan.grid.area();
  const nlohmann::json j = {{"version", FullVersionString()},
                            {"tile_size_m", plan.options.tile_size_m},
                            {"halo_m", plan.options.halo_m},
                            {"window_margin_px", plan.options.window_margin_px},
                            {"z_range_m", {plan.z_min_m, plan.z_max_m}},
                            {"z_source", plan.z_source},
                            {"area", BoxJson(area)},
                            {"grid", {plan.grid.num_x(), plan.grid.num_y()}},
                            {"bytes_per_window_pixel", kTileBytesPerWindowPixel},
                            {"tiles", tiles}};
  nlohmann::json out = j;
  if (!config_hash.empty()) out["config_hash"] = config_hash;
  if (!inputs_hash.empty()) out["inputs_hash"] = inputs_hash;
  return JsonText(out, 2) + "\n";
}

TilePlan SharedTilePlan(const JobConfig& config, const DepthBlock& input, const std::vector<ViewIdentity>& identities,
                        std::string* plan_path) {
  TilePlan plan = BuildTilePlan(input, config.tiling);
  const std::string hash = ResultSettingsHash(config);
  const std::string inputs_hash = IdentitiesDigest(identities);
  const std::string path = PlanJsonPath(config);
  const std::string text = TilePlanJson(plan, input, hash, inputs_hash);
  if (plan_path != nullptr) *plan_path = path;
  std::ifstream in(path);
  nlohmann::json existing;
  if (in) {
    try {
      existing = nlohmann::json::parse(in);
    } catch (const std::exception&) {
      existing = nullptr;  // half-written by hand or foreign: rewrite
    }
  }
  const bool same_settings = existing.is_object() && existing.value("config_hash", "") == hash;
  if (same_settings && existing.value("inputs_hash", "") != inputs_hash) {
    spdlog::info("plan: the inputs changed since {} was written: re-planned", path);
  } else if (same_settings) {
    nlohmann::json mine = nlohmann::json::parse(text);
    for (const char* label : {"version", "z_source"}) {  // labels: a plan of an older version names them otherwise
      mine.erase(label);
      existing.erase(label);
    }
    if (mine != existing) {
      throw Error(path + ": the shared plan of this config differs from the plan built here (inputs changed?); "
                         "delete it to re-plan");
    }
    spdlog::debug("plan: using the shared {}", path);
    return plan;
  }
  std::filesystem::create_directories(config.output.dir);
  WriteFileAtomically(path, text);
  spdlog::info("plan: {} tiles ({} x {}), z range [{:.1f}, {:.1f}] m from {}, written to {}", plan.tiles.size(),
               plan.grid.num_x(), plan.grid.num_y(), plan.z_min_m, plan.z_max_m, plan.z_source, path);
  return plan;
}

}  // namespace sacfuse
