#include "jobs/run_fusion.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/backproject.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/depth_block.h"
#include "jobs/open_input.h"
#include "io/las_crs.h"
#include "io/las_writer.h"
#include "jobs/auto_tiling.h"
#include "jobs/memory_model.h"
#include "jobs/method_block.h"
#include "jobs/report_input_counts.h"
#include "jobs/report_writer.h"
#include "jobs/resource_usage.h"
#include "jobs/thread_limit.h"
#include "jobs/sac_block.h"
#include "jobs/tiled_run.h"
#include "jobs/version.h"

namespace sacfuse {
namespace {

// Counts points per source view on their way to the real sink.
class CountingSink : public PointSink {
 public:
  explicit CountingSink(PointSink& next) : next_(next) {}
  void Write(const FusedPoint* points, size_t count) override {
    for (size_t i = 0; i < count; ++i) {
      if (points[i].view_index >= per_view_.size()) per_view_.resize(points[i].view_index + 1, 0);
      ++per_view_[points[i].view_index];
    }
    next_.Write(points, count);
  }
  uint64_t count(uint32_t view) const { return view < per_view_.size() ? per_view_[view] : 0; }

 private:
  PointSink& next_;
  std::vector<uint64_t> per_view_;
};


nlohmann::json MethodStatsJson(const MethodStats& m, bool tiled) {
  nlohmann::json counters = nlohmann::json::object();
  for (const auto& [name, n] : m.counters) counters[name] = n;
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [stage, secs] : m.stage_seconds) stages[stage] = secs;
  // Tiled: emitted and the counters include the points each tile computed in its halo (left to its neighbours).
  return {{"pixels_in", m.input_pixels}, {"points_emitted", m.emitted}, {"emitted_includes_halos", tiled},
          {"counters", counters}, {"stage_seconds", stages}};
}

void WriteRunReport(const RunSummary& s, const JobConfig& config) {
  nlohmann::json views = nlohmann::json::array();
  for (const auto& v : s.views) {
    views.push_back({{"name", v.name}, {"input_pixels", v.input_pixels}, {"output_points", v.output_points}});
  }
  nlohmann::json j = {{"version", VersionString()},
                            {"config", config.source_file},
                            {"method", s.method},
                            {"fused_las", s.las_path},
                            {"input_points", s.input_points},
                            {"output_points", s.output_points},
                            {"wall_seconds", s.wall_seconds},
                            {"cpu_seconds", s.cpu_seconds},
                            {"peak_rss_mib", s.peak_rss_mib},
                            {"threads", s.threads},
                            {"memory", {{"budget_gib", s.memory_budget_gib}, {"estimate_gib", s.memory_estimate_gib}}},
                            {"tiling_decision", {{"tile_size_m", s.tile_size_m}, {"reason", s.tiling_reason}}},
                            {"stage_wall_seconds",
                             {{"superpixels", s.superpixel_seconds}, {"tiles", s.tiles_seconds},
                              {"merge", s.merge_seconds}}},
                            {"views", views}};
  if (s.has_sac_stats) {
    nlohmann::json stages = nlohmann::json::object();
    for (const auto& [stage, secs] : s.sac.stage_seconds) stages[stage] = secs;
    j["sac"] = {{"nodes", s.sac.nodes},
                {"valid_nodes", s.sac.valid_nodes},
                {"mean_correspondences", s.sac.mean_correspondences},
                {"netlets", s.sac.labeling.netlets},
                {"netlets_proven_optimal", s.sac.labeling.proven_optimal},
                {"netlet_size_histogram", s.sac.labeling.size_histogram},
                {"nodes_keeping_own_view", s.sac.labeling.nodes_keeping_own_view},
                {"nodes_relabelled", s.sac.labeling.nodes_relabelled},
                {"pixels_in", s.sac.collapse.input_pixels},
                {"pixels_collapsed", s.sac.collapse.collapsed},
                {"pixels_kept_uncovered", s.sac.collapse.kept_uncovered},
                {"pixels_outliers", s.sac.collapse.outliers},
                {"points_emitted", s.sac.collapse.emitted},
                {"superpixels_computed", s.superpixels_computed},
                {"stage_seconds", stages}};
    if (!s.sac.noise_factor.empty()) {
      // Estimated depth noise of the views (core/view_noise.h): sigma = k z^2 / focal metres.
      std::vector<double> k = s.sac.noise_factor;
      std::sort(k.begin(), k.end());
      j["sac"]["noise_factor"] = {{"min", k.front()}, {"median", k[k.size() / 2]}, {"max", k.back()}};
    }
  }
  if (s.tiles_run > 0) {
    nlohmann::json failed = nlohmann::json::array();
    for (const auto& [id, reason] : s.failed_tiles) failed.push_back({{"id", id}, {"reason", reason}});
    j["tiling"] = {{"tile_size_m", config.tiling.tile_size_m}, {"halo_m", config.tiling.halo_m},
                   {"tiles_run", s.tiles_run}, {"tiles_computed", s.tiles_computed},
                   {"tiles_skipped", s.tiles_skipped}, {"failed_tiles", failed}};
  }
  if (s.has_method_stats) j["fusion"] = MethodStatsJson(s.method_stats, s.tiles_run > 0);
  WriteFileAtomically(s.report_path, j.dump(2) + "\n");
}

void CheckRerunTiles(const std::vector<std::string>& rerun_tiles, const TilePlan* plan) {
  if (rerun_tiles.empty()) return;
  if (!plan) throw ConfigError("--tiles: only tiled runs have tiles (tiling.tile_size_m > 0, or a block too big for the memory budget)");
  const std::vector<std::string> known = TileIdsWithViews(*plan);
  std::string unknown;
  for (const auto& id : rerun_tiles) {
    if (std::find(known.begin(), known.end(), id) == known.end()) unknown += (unknown.empty() ? "" : ", ") + id;
  }
  if (!unknown.empty()) {
    throw ConfigError("--tiles: unknown tile ids: " + unknown + " (tiles with views: see `sacfuse status` or "
                      "`sacfuse plan`)");
  }
}

void LogSacStats(const SacStats& s) {
  spdlog::info("SAC: {} nodes in {} Netlets ({} proven optimal); {} pixels in, {} collapsed, {} outliers, {} out",
               s.valid_nodes, s.labeling.netlets, s.labeling.proven_optimal, s.collapse.input_pixels,
               s.collapse.collapsed, s.collapse.outliers, s.collapse.emitted);
}

void SetSacSummary(const SacBlockResult& sac, RunSummary* summary) {
  summary->has_sac_stats = true;
  summary->sac = sac.stats;
  summary->superpixels_computed = sac.superpixels_computed;
  summary->superpixel_seconds = sac.superpixel_seconds;
  summary->input_points = sac.stats.collapse.input_pixels;
  LogSacStats(sac.stats);
}

// Comparison methods (jobs/fusion_methods.h): input counts per view and the method's counters.
void SetMethodSummary(const MethodStats& stats, RunSummary* summary) {
  summary->has_method_stats = true;
  summary->method_stats = stats;
  summary->input_points = stats.input_pixels;
  for (size_t i = 0; i < summary->views.size() && i < stats.input_per_view.size(); ++i) {
    summary->views[i].input_pixels = stats.input_per_view[i];
  }
  std::string counters;
  for (const auto& [name, n] : stats.counters) counters += fmt::format(", {} {}", name, n);
  spdlog::info("{}: {} pixels in, {} points emitted{}", summary->method, stats.input_pixels, stats.emitted, counters);
}

std::string CacheDir(const JobConfig& config) {
  return config.fusion.superpixel_cache_dir.empty()
             ? (std::filesystem::path(config.output.dir) / "superpixels").string()
             : config.fusion.superpixel_cache_dir;
}

// Tiled (any method): per-tile files, resume, merge (jobs/tiled_run.h).
void RunTiled(const JobConfig& config, const DepthBlock& input, const RunProgress& progress,
              const std::vector<std::string>& rerun_tiles, RunSummary* summary) {
  const TilePlan plan = SharedTilePlan(config, input);
  CheckRerunTiles(rerun_tiles, &plan);
  spdlog::info("tiled {}: {} tiles of {} m ({} x {}), halo {} m, z range [{:.1f}, {:.1f}] m from {}",
               config.fusion.method, plan.tiles.size(), config.tiling.tile_size_m, plan.grid.num_x(), plan.grid.num_y(),
               config.tiling.halo_m, plan.z_min_m, plan.z_max_m, plan.z_source);
  const TiledRunOutcome tiled =
      RunTiledSac(config, input, plan, rerun_tiles, MakeLasOptions(config), summary->las_path, progress);
  if (config.fusion.method == "sac") {
    SetSacSummary(tiled.block, summary);
  } else {
    SetMethodSummary(tiled.method_stats, summary);
  }
  summary->tiles_run = tiled.tiles_with_views;
  summary->tiles_computed = tiled.tiles_computed;
  summary->tiles_skipped = tiled.tiles_skipped;
  summary->failed_tiles = tiled.failed;
  summary->tiles_seconds = tiled.tiles_seconds;
  summary->merge_seconds = tiled.merge_seconds;
  summary->output_points = tiled.merged_points;
  for (auto& v : summary->views) {
    const size_t i = &v - summary->views.data();
    v.output_points = i < tiled.points_per_view.size() ? tiled.points_per_view[i] : 0;
  }
  spdlog::info("tiles: {} computed, {} done and skipped, {} failed", tiled.tiles_computed, tiled.tiles_skipped,
               tiled.failed.size());
}

// Untiled: SAC, the union (streamed view by view) or a comparison method, into one LAS writer.
void RunUntiled(const JobConfig& config, const DepthBlock& input, const RunProgress& progress,
                RunSummary* summary) {
  const auto& views = input.views();
  LasWriter writer(summary->las_path, MakeLasOptions(config));
  CountingSink counting(writer);
  if (config.fusion.method == "union") {
    spdlog::info("fusion method: union (every valid depth pixel becomes a point; no fusion)");
    for (size_t i = 0; i < views.size(); ++i) {
      const DepthMap depth = input.ReadDepthMap(views[i]);
      const RgbImage image = input.ReadImage(views[i]);
      summary->views[i].input_pixels = BackprojectDepthMap(views[i], depth, &image, counting);
      summary->input_points += summary->views[i].input_pixels;
      if (progress) progress("fuse", i + 1, views.size());
    }
  } else if (config.fusion.method != "sac") {
    SetMethodSummary(FuseWorkspaceWithMethod(input, config, counting, progress).stats, summary);
  } else {
    SetSacSummary(FuseWorkspaceWithSac(input, config.fusion.sac, CacheDir(config), counting, progress),
                  summary);
  }
  writer.Close();
  summary->output_points = writer.num_points();
  for (size_t i = 0; i < views.size(); ++i) summary->views[i].output_points = counting.count(views[i].index);
}

}  // namespace

LasWriterOptions MakeLasOptions(const OutputOptions& output) {
  LasWriterOptions o;
  o.version_minor = output.las_version == "1.2" ? 2 : 4;
  o.scale_m = output.scale_m;
  o.generating_software = VersionString();
  return o;
}

LasWriterOptions MakeLasOptions(const JobConfig& config) {
  LasWriterOptions o = MakeLasOptions(config.output);
  AddCrsToLasOptions(ParseProjectCrs(config.crs), &o);
  return o;
}

std::string FusedLasPath(const JobConfig& config) {
  return (std::filesystem::path(config.output.dir) / "fused.las").string();
}

RunSummary RunFusionJob(const JobConfig& given, const RunProgress& progress,
                        const std::vector<std::string>& rerun_tiles) {
  ValidateJobConfig(given);
  JobConfig config = given;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ProcessCpuSeconds();
  std::filesystem::create_directories(config.output.dir);

  RunSummary summary;
  summary.method = config.fusion.method;
  summary.las_path = FusedLasPath(config);
  summary.effective_config_path = (std::filesystem::path(config.output.dir) / "sacfuse.effective.yaml").string();
  summary.report_path = (std::filesystem::path(config.output.dir) / "run_report.json").string();
  WriteFileAtomically(summary.effective_config_path, DumpJobConfig(config, true));

  const std::unique_ptr<DepthBlock> block = OpenNonEmptyInput(config.input, "fuse", config.crs);
  const DepthBlock& input = *block;
  const auto& views = input.views();
  TilingDecision decision;
  config = ResolveTiling(given, input, &decision);
  const ThreadLimit thread_limit(EffectiveThreads(config));
  summary.threads = EffectiveThreads(config);
  summary.tile_size_m = config.tiling.tile_size_m;
  summary.tiling_reason = decision.reason;
  summary.memory_budget_gib = config.resources.memory_gb;
  summary.memory_estimate_gib =
      static_cast<double>(decision.tiled ? decision.max_tile_bytes : decision.untiled_bytes) / kGiB;
  const bool tiled = config.tiling.tile_size_m > 0;  // every method (union only when given a tile size)
  if (!tiled) CheckRerunTiles(rerun_tiles, nullptr);
  if (given.tiling.tile_size_m != config.tiling.tile_size_m) {
    WriteFileAtomically(summary.effective_config_path, DumpJobConfig(config, true));  // with the size chosen
  }
  spdlog::info("input: {} views from {}", views.size(), config.input.path);
  summary.views.resize(views.size());
  for (size_t i = 0; i < views.size(); ++i) summary.views[i].name = views[i].name;
  if (config.fusion.method == "sac") {
    spdlog::info("fusion method: sac (Select-and-Combine, unary '{}', correspondences '{}')",
                 config.fusion.sac.unary, config.fusion.sac.correspondence);
  } else if (config.fusion.method != "union") {
    spdlog::info("fusion method: {} (comparison method; no superpixels)", config.fusion.method);
  }
  if (tiled) {
    RunTiled(config, input, progress, rerun_tiles, &summary);
  } else {
    RunUntiled(config, input, progress, &summary);
  }
  if (config.fusion.method == "sac") {  // per-view valid depth pixels ("before" counts) from the superpixel tables
    const std::vector<uint64_t> valid = ValidDepthPixelsPerView(input, CacheDir(config));
    summary.input_points = 0;
    for (size_t i = 0; i < views.size(); ++i) summary.input_points += summary.views[i].input_pixels = valid[i];
  }

  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.cpu_seconds = ProcessCpuSeconds() - cpu_start;
  summary.peak_rss_mib = PeakRssMiB();
  WriteRunReport(summary, config);
  WriteHtmlReportOrWarn(config);  // DIR/report/index.html; a failure is only a warning
  if (summary.failed_tiles.empty()) {
    spdlog::info("wrote {} points to {} in {:.1f} s (peak RSS {:.0f} MiB)", summary.output_points, summary.las_path,
                 summary.wall_seconds, summary.peak_rss_mib);
  }
  return summary;
}

}  // namespace sacfuse
