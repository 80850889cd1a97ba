#include "report/report_data.h"

#include <chrono>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "io/las_reader.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

bool ReadText(const fs::path& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream os;
  os << in.rdbuf();
  *text = os.str();
  return true;
}

std::string Now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%d %H:%M", &tm);
  return buf;
}

// "3_4" -> (3, 4); false for anything else.
bool ParseTileId(const std::string& id, int* ix, int* iy) {
  const size_t sep = id.find('_');
  if (sep == std::string::npos || sep == 0 || sep + 1 >= id.size()) return false;
  try {
    size_t a = 0, b = 0;
    *ix = std::stoi(id.substr(0, sep), &a);
    *iy = std::stoi(id.substr(sep + 1), &b);
    return a == sep && b == id.size() - sep - 1;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

ReportRun ParseRunReportJson(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  ReportRun r;
  r.present = true;
  r.version = j.value("version", "");
  r.method = j.value("method", "");
  r.config_path = j.value("config", "");
  r.input_points = j.value("input_points", uint64_t{0});
  r.output_points = j.value("output_points", uint64_t{0});
  r.wall_seconds = j.value("wall_seconds", 0.0);
  r.cpu_seconds = j.value("cpu_seconds", 0.0);
  r.peak_rss_mib = j.value("peak_rss_mib", 0.0);
  r.threads = j.value("threads", 0);
  if (j.contains("memory")) {
    r.memory_budget_gib = j["memory"].value("budget_gib", 0.0);
    r.memory_estimate_gib = j["memory"].value("estimate_gib", 0.0);
  }
  if (j.contains("tiling_decision")) {
    r.tile_size_m = j["tiling_decision"].value("tile_size_m", 0.0);
    r.tiling_reason = j["tiling_decision"].value("reason", "");
  }
  if (j.contains("stage_wall_seconds")) {
    r.superpixel_seconds = j["stage_wall_seconds"].value("superpixels", 0.0);
    r.tiles_seconds = j["stage_wall_seconds"].value("tiles", 0.0);
    r.merge_seconds = j["stage_wall_seconds"].value("merge", 0.0);
  }
  if (j.contains("views")) {
    uint32_t index = 0;
    for (const auto& v : j.at("views")) {
      ViewCounts c;
      c.view = index++;
      c.name = v.value("name", "");
      c.before = v.value("input_pixels", uint64_t{0});
      c.after = v.value("output_points", uint64_t{0});
      r.views.push_back(c);
    }
  }
  if (j.contains("warnings")) r.input_warnings = j.at("warnings").get<std::vector<std::string>>();
  if (j.contains("sac")) {
    const auto& s = j["sac"];
    r.has_sac = true;
    r.sac_nodes = s.value("valid_nodes", uint64_t{0});
    r.sac_netlets = s.value("netlets", uint64_t{0});
    r.sac_nodes_relabelled = s.value("nodes_relabelled", uint64_t{0});
    r.sac_pixels_collapsed = s.value("pixels_collapsed", uint64_t{0});
    r.sac_pixels_kept_uncovered = s.value("pixels_kept_uncovered", uint64_t{0});
    r.sac_pixels_outliers = s.value("pixels_outliers", uint64_t{0});
    if (s.contains("tiling") || j.contains("tiling")) {
      const auto& t = j.contains("tiling") ? j["tiling"] : s["tiling"];
      for (const auto& f : t.value("failed_tiles", nlohmann::json::array())) {
        r.failed_tiles.emplace_back(f.value("id", ""), f.value("reason", ""));
      }
    }
  }
  return r;
}

ReportEval ParseEvalJson(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  ReportEval e;
  e.present = true;
  for (const auto& s : j.at("scores")) {
    e.scores.push_back({s.at("tau_m").get<double>(), s.at("accuracy").get<double>(),
                        s.at("completeness").get<double>(), s.at("f1").get<double>()});
  }
  e.mean_abs_distance_m = j.value("mean_abs_distance_m", 0.0);
  e.median_abs_distance_m = j.value("median_abs_distance_m", 0.0);
  e.result_points_evaluated = j.value("result_points_evaluated", uint64_t{0});
  e.reference_points_evaluated = j.value("reference_points_evaluated", uint64_t{0});
  e.result_stride = j.value("result_stride", uint64_t{1});
  e.aligned = j.value("aligned", false);
  return e;
}

std::vector<ReportTile> GatherTiles(const JobConfig& given, std::vector<std::string>* warnings) {
  std::vector<ReportTile> tiles;
  const std::string tiles_dir = TilesDir(given);
  std::optional<TileManifest> manifest;
  try {
    manifest = TileManifest::Read(tiles_dir);
  } catch (const std::exception& e) {
    warnings->push_back(std::string(e.what()) + ": no tile map");
    return tiles;
  }
  if (!manifest) {
    warnings->push_back("tiled run without " + TileManifest::Path(tiles_dir) + ": no tile map");
    return tiles;
  }
  JobConfig config = given;
  if (config.tiling.tile_size_m <= 0) config.tiling.tile_size_m = manifest->tile_size_m;
  const std::string hash = ResultSettingsHash(config);
  // Core bounds and estimates from plan.json.
  std::map<std::string, std::pair<Box2d, uint64_t>> planned;
  std::string text;
  if (ReadText(PlanJsonPath(config), &text)) {
    try {
      const nlohmann::json plan = nlohmann::json::parse(text);
      for (const auto& t : plan.at("tiles")) {
        const auto core = t.at("core").get<std::vector<double>>();
        if (core.size() != 4) continue;
        Box2d b;
        b.min = {core[0], core[1]};
        b.max = {core[2], core[3]};
        planned[t.at("id").get<std::string>()] = {b, t.value("memory_bytes", uint64_t{0})};
      }
    } catch (const std::exception& e) {
      warnings->push_back(config.output.dir + "/plan.json unreadable (" + e.what() + "): tiles placed by id");
    }
  }
  // Every tile's state read in parallel (each reads its marker and its file's header), then taken in the
  // manifest's order: a tile whose state cannot be read ends the list there with a warning.
  struct TileState {
    std::optional<ReportTile> tile;  // unset: not a tile id
    std::exception_ptr error;
  };
  std::vector<TileState> states(manifest->tiles.size());
  tbb::parallel_for(size_t{0}, states.size(), [&](size_t i) {
    try {
      ReportTile t;
      t.id = manifest->tiles[i];
      if (!ParseTileId(t.id, &t.ix, &t.iy)) return;
      if (const auto it = planned.find(t.id); it != planned.end()) {
        t.has_core = true;
        t.core = it->second.first;
        t.memory_estimate_bytes = it->second.second;
      }
      const TileCheck check = VerifyTileDone(tiles_dir, t.id, hash, /*full_checksum=*/false);
      if (check.done) {
        t.status = TileStatus::kDone;
        if (const auto m = ReadTileDoneMarker(tiles_dir, t.id)) {
          t.points = m->points;
          t.file = TileCloudPath(tiles_dir, *m);
          t.views = m->views;
          t.seconds = m->seconds;
          t.peak_rss_mib = m->peak_rss_mib;
        }
      } else if (const auto reason = ReadTileFailedReason(tiles_dir, t.id)) {
        t.status = TileStatus::kFailed;
        t.reason = *reason;
      } else {
        t.status = TileStatus::kPending;
        t.reason = check.reason;
      }
      states[i].tile = std::move(t);
    } catch (...) {
      states[i].error = std::current_exception();
    }
  });
  for (TileState& state : states) {
    if (state.error) {
      try {
        std::rethrow_exception(state.error);
      } catch (const std::exception& e) {
        warnings->push_back(tiles_dir + ": tile states unreadable (" + e.what() + ")");
      }
      break;
    }
    if (state.tile) tiles.push_back(std::move(*state.tile));
  }
  return tiles;
}

ReportData GatherReportData(const JobConfig& config) {
  ReportData d;
  d.output_dir = config.output.dir;
  d.generated_at = Now();
  d.reference_path = config.evaluation.reference;
  std::string text;
  if (ReadText(RunReportPath(config), &text)) {
    try {
      d.run = ParseRunReportJson(text);
    } catch (const std::exception& e) {
      d.warnings.push_back(RunReportPath(config) + " unreadable (" + e.what() + ")");
    }
  } else {
    d.warnings.push_back("no " + RunReportPath(config) + ": run numbers missing");
  }
  if (!ReadText(EffectiveConfigPath(config), &d.effective_config)) {
    d.warnings.push_back("no " + EffectiveConfigPath(config));
  }
  d.cloud.path = FusedLasPath(config);
  d.cloud.name = fs::path(d.cloud.path).filename().string();
  std::error_code ec;
  if (fs::exists(d.cloud.path, ec)) {
    try {
      const LasHeader h = LasReader(d.cloud.path).header();
      d.cloud.exists = true;
      d.cloud.points = h.point_count;
      for (int a = 0; a < 3; ++a) {
        d.cloud.min[a] = h.min[a];
        d.cloud.max[a] = h.max[a];
      }
    } catch (const std::exception& e) {
      d.warnings.push_back(fs::path(d.cloud.path).filename().string() + " unreadable: " + e.what());
    }
  }
  const fs::path eval_path = EvalJsonPath(config);
  if (fs::exists(eval_path, ec)) {
    const bool stale =
        d.cloud.exists && fs::last_write_time(eval_path, ec) < fs::last_write_time(d.cloud.path, ec);
    if (stale) {
      d.eval.stale = true;
    } else if (ReadText(eval_path, &text)) {
      try {
        d.eval = ParseEvalJson(text);
      } catch (const std::exception& e) {
        d.warnings.push_back(eval_path.string() + " unreadable (" + e.what() + ")");
      }
    }
  }
  d.tile_size_m = d.run.present ? d.run.tile_size_m : 0.0;
  d.tiled = d.run.present ? d.run.tile_size_m > 0 : fs::exists(TileManifest::Path(TilesDir(config)), ec);
  if (d.tiled) d.tiles = GatherTiles(config, &d.warnings);
  return d;
}

}  // namespace sacfuse
