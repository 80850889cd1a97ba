#include "jobs/run_fusion.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
#include <tbb/task_group.h>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "config/version.h"
#include "core/error.h"
#include "core/superpixels.h"
#include "eval/eval_runner.h"
#include "io/atomic_file.h"
#include "io/depth_block.h"
#include "io/input_warnings.h"
#include "io/json_text.h"
#include "io/point_cloud_writer.h"
#include "io/resource_usage.h"
#include "io/test_pause.h"
#include "io/view_identity.h"
#include "jobs/auto_tiling.h"
#include "jobs/block_view_source.h"
#include "jobs/coregistered_block.h"
#include "jobs/fuse_views.h"
#include "jobs/fusion_methods.h"
#include "jobs/job_report.h"
#include "jobs/las_options.h"
#include "jobs/method_geometry.h"
#include "jobs/open_input.h"
#include "jobs/output_lock.h"
#include "jobs/point_sinks.h"
#include "jobs/run_state.h"
#include "jobs/thread_limit.h"
#include "jobs/tiled_run.h"
#include "tiles/memory_model.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_plan.h"

namespace sacfuse {
namespace {

nlohmann::json FusionStatsJson(const FusionStats& m, bool tiled) {
  nlohmann::json counters = nlohmann::json::object();
  for (const auto& [name, n] : m.counters) counters[name] = n;
  nlohmann::json histograms = nlohmann::json::object();
  for (const auto& [name, bins] : m.histograms) histograms[name] = bins;
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [stage, secs] : m.stage_seconds) stages[stage] = secs;
  // Tiled: emitted and the counters include the points each tile computed in its halo (left to its neighbours).
  return {{"pixels_in", m.input_pixels}, {"points_emitted", m.emitted}, {"emitted_includes_halos", tiled},
          {"counters", counters}, {"histograms", histograms}, {"stage_seconds", stages}};
}

// SAC's counters under the names the HTML report reads (report/report_data.h).
nlohmann::json SacSectionJson(const FusionStats& f, size_t superpixels_computed) {
  const uint64_t valid_nodes = f.counter("valid_nodes");
  const uint64_t labelled_nodes = f.counter("labelled_nodes");
  const std::vector<uint64_t>* sizes = f.histogram("netlet_size");
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [stage, secs] : f.stage_seconds) stages[stage] = secs;
  nlohmann::json j = {
      {"nodes", f.counter("nodes")},
      {"valid_nodes", valid_nodes},
      {"labelled_nodes", labelled_nodes},
      {"mean_correspondences",  // per labelled node
       labelled_nodes > 0 ? static_cast<double>(f.counter("correspondences")) / static_cast<double>(labelled_nodes)
                          : 0.0},
      {"netlets", f.counter("netlets")},
      {"netlets_proven_optimal", f.counter("netlets_proven_optimal")},
      {"netlet_size_histogram", sizes != nullptr ? *sizes : std::vector<uint64_t>{}},
      {"nodes_keeping_own_view", f.counter("nodes_keeping_own_view")},
      {"nodes_relabelled", f.counter("nodes_relabelled")},
      {"pixels_in", f.counter("pixels_in")},
      {"pixels_collapsed", f.counter("pixels_collapsed")},
      {"pixels_kept_uncovered", f.counter("pixels_kept_uncovered")},
      {"pixels_outliers", f.counter("pixels_outliers")},
      {"points_emitted", f.emitted},
      {"superpixels_computed", superpixels_computed},
      {"stage_seconds", stages}};
  const std::vector<double>* noise = f.view_value("noise_factor");
  if (noise != nullptr && !noise->empty()) {
    // Estimated depth noise of the views (core/view_noise.h): sigma = k z^2 / focal metres.
    std::vector<double> k = *noise;
    std::sort(k.begin(), k.end());
    j["noise_factor"] = {{"min", k.front()}, {"median", k[k.size() / 2]}, {"max", k.back()}};
  }
  return j;
}

// Every stage so far, in order, with the whole job's time (io/stage_clock.h).
nlohmann::json StagesJson(const RunSummary& s) {
  nlohmann::json list = nlohmann::json::array();
  for (const StageTime& t : s.stages) {
    list.push_back({{"name", t.name}, {"wall_s", t.wall_s}, {"cpu_s", t.cpu_s}, {"peak_rss_mib", t.peak_rss_mib},
                    {"rss_mib", t.rss_mib}});
  }
  nlohmann::json j = {{"threads", s.threads}, {"list", list}, {"total_wall_s", s.total_wall_seconds},
                      {"total_cpu_s", s.total_cpu_seconds}};
  if (s.tiles_run == 0) j["fusion_writer_wall_s"] = s.write_seconds;  // untiled: part of the "fusion" stage
  return j;
}

void WriteRunReport(const RunSummary& s, const JobConfig& config) {
  nlohmann::json views = nlohmann::json::array();
  for (const auto& v : s.views) {
    views.push_back({{"name", v.name}, {"input_pixels", v.input_pixels}, {"output_points", v.output_points}});
  }
  nlohmann::json j = {{"version", FullVersionString()},
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
                             {{"coregistration", s.coregistration.seconds}, {"superpixels", s.superpixel_seconds},
                              {"tiles", s.tiles_seconds}, {"merge", s.merge_seconds}, {"dsm", s.dsm.seconds},
                              {"ortho", s.ortho.seconds}}},
                            {"stages", StagesJson(s)},
                            {"views", views}};
  if (s.coregistration.enabled) {
    const CoregistrationOutcome& c = s.coregistration;
    const CoregistrationSummary& m = c.summary;
    j["coregistration"] = {{"file", CoregistrationPath(config)}, {"reused", c.reused}, {"seconds", c.seconds},
                           {"median_rotation_deg", m.median_rotation_deg}, {"max_rotation_deg", m.max_rotation_deg},
                           {"median_shift_m", m.median_shift_m}, {"max_shift_m", m.max_shift_m},
                           {"median_rms_before_m", m.median_rms_before_m},
                           {"median_rms_after_m", m.median_rms_after_m}};
  }
  if (s.method == "sac") j["sac"] = SacSectionJson(s.fusion, s.superpixels_computed);
  if (s.tiles_run > 0) {
    nlohmann::json failed = nlohmann::json::array();
    for (const auto& [id, reason] : s.failed_tiles) failed.push_back({{"id", id}, {"reason", reason}});
    j["tiling"] = {{"tile_size_m", config.tiling.tile_size_m}, {"halo_m", config.tiling.halo_m},
                   {"tiles_run", s.tiles_run}, {"tiles_computed", s.tiles_computed},
                   {"tiles_skipped", s.tiles_skipped}, {"failed_tiles", failed}};
  }
  j["fusion"] = FusionStatsJson(s.fusion, s.tiles_run > 0);
  if (s.dsm.written) {
    const DsmOutcome& d = s.dsm;
    j["dsm"] = {{"file", d.path}, {"cell_m", d.cell_m}, {"cols", d.cols}, {"rows", d.rows},
                {"cells_with_value", d.cells_with_value}, {"cells_from_points", d.raw_cells_with_value},
                {"cells_filled", d.cells_filled}, {"files", d.files},
                {"seconds", d.seconds}};
  }
  if (s.ortho.written) {
    const OrthoOutcome& o = s.ortho;
    j["ortho"] = {{"file", o.path}, {"cols", o.cols}, {"rows", o.rows}, {"cells_coloured", o.cells_coloured},
                  {"cells_selected_view", o.cells_selected_view}, {"cells_other_view", o.cells_other_view},
                  {"cells_unseen", o.cells_unseen}, {"image_reads", o.image_reads}, {"files", o.files},
                  {"seconds", o.seconds}, {"cpu_seconds", o.cpu_seconds}, {"peak_rss_mib", o.peak_rss_mib}};
  }
  // Warnings about the input, among them every default that replaced missing input data (io/input_warnings.h).
  j["warnings"] = InputWarningsGiven();
  WriteFileAtomically(s.report_path, JsonText(j, 2) + "\n");
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

// The method's stats: input counts per view, counters in the log.
void SetFusionSummary(const FusionStats& stats, RunSummary* summary) {
  summary->fusion = stats;
  summary->input_points = stats.input_pixels;
  for (size_t i = 0; i < summary->views.size() && i < stats.input_per_view.size(); ++i) {
    summary->views[i].input_pixels = stats.input_per_view[i];
  }
  std::string counters;
  for (const auto& [name, n] : stats.counters) counters += fmt::format(", {} {}", name, n);
  spdlog::info("{}: {} pixels in, {} points emitted{}", summary->method, stats.input_pixels, stats.emitted, counters);
}

// Tiled (any method): per-tile files, resume, merge (jobs/tiled_run.h).
void RunTiled(const JobConfig& config, const DepthBlock& input, const RunProgress& progress,
              const std::vector<std::string>& rerun_tiles, size_t views_in_flight,
              const std::vector<ViewIdentity>& pinned, OutputWriterLock& lock, StageClock* clock,
              RunSummary* summary) {
  const BlockIdentity identity = IdentifyBlock(input);
  spdlog::info("input identities of {} views: {:.2f} MiB read and hashed in {:.3f} s ({:.0f} MiB/s)",
               identity.views.size(), static_cast<double>(identity.bytes_hashed) / (1 << 20), identity.seconds,
               identity.seconds > 0 ? static_cast<double>(identity.bytes_hashed) / (1 << 20) / identity.seconds : 0.0);
  lock.Record(ResultSettingsHash(config), IdentitiesDigest(identity.views));  // `sacfuse tile` workers compare
  const TilePlan plan = SharedTilePlan(config, input, identity.views);
  CheckRerunTiles(rerun_tiles, &plan);
  spdlog::info("tiled {}: {} tiles of {} m ({} x {}), halo {} m, z range [{:.1f}, {:.1f}] m from {}",
               NameOf(config.fusion.method), plan.tiles.size(), config.tiling.tile_size_m, plan.grid.num_x(), plan.grid.num_y(),
               config.tiling.halo_m, plan.z_min_m, plan.z_max_m, plan.z_source);
  const TiledRunOutcome tiled = RunTiledJob(config, input, plan, identity.views, rerun_tiles, summary->las_path,
                                            progress, views_in_flight, &pinned, clock);
  SetFusionSummary(tiled.stats, summary);
  summary->superpixels_computed = tiled.superpixels_computed;
  summary->superpixel_seconds = tiled.superpixel_seconds;
  summary->tiles_run = tiled.tiles_with_views;
  summary->tiles_computed = tiled.tiles_computed;
  summary->tiles_skipped = tiled.tiles_skipped;
  summary->failed_tiles = tiled.failed;
  summary->tiles_seconds = tiled.tiles_seconds;
  summary->merge_seconds = tiled.merge_seconds;
  summary->dsm = tiled.dsm;
  summary->ortho = tiled.ortho;
  summary->output_points = tiled.merged_points;
  for (auto& v : summary->views) {
    const size_t i = &v - summary->views.data();
    v.output_points = i < tiled.points_per_view.size() ? tiled.points_per_view[i] : 0;
  }
  spdlog::info("tiles: {} computed, {} done and skipped, {} failed", tiled.tiles_computed, tiled.tiles_skipped,
               tiled.failed.size());
}

// Untiled: the whole block through the same FuseViews as every tile, into one cloud writer. The fusion's memory
// is released before the writer is closed (a COPC is built out of core in Close, within the budget).
void RunUntiled(const JobConfig& config, const DepthBlock& input, const RunProgress& progress,
                size_t views_in_flight, const std::vector<ViewIdentity>& pinned, StageClock* clock,
                RunSummary* summary) {
  const auto& views = input.views();
  const std::unique_ptr<PointCloudWriter> writer = OpenPointCloudWriter(summary->las_path, FusedCloudOptions(config));
  TimedSink timed_writer(*writer);
  FusedViews fused;
  bool superpixels = false;
  const std::string cache_dir = SuperpixelCacheDir(config);
  {
    const std::unique_ptr<FusionMethod> method = MakeFusionMethod(config.fusion, progress);
    superpixels = method->needs().superpixels;
    MethodGeometry geometry;
    if (method->needs().block_geometry) {
      std::vector<DepthRasterSize> sizes;
      for (const View& view : views) sizes.push_back(input.DepthSize(view));
      double z_min = 0, z_max = 0;
      std::string z_source;
      BlockHeightRange(input, config.tiling, &z_min, &z_max, &z_source);
      geometry = BlockMethodGeometry(input, sizes, z_min, z_max, NeighborOptionsOf(config.fusion.sac));
      spdlog::info("{}: block GSD {:.3f} m from the geometry (heights [{:.1f}, {:.1f}] m from {})",
                   NameOf(config.fusion.method), geometry.gsd_m, z_min, z_max, z_source);
    }
    const BlockViewSource source(input, config.fusion.sac.superpixels, cache_dir, progress, views_in_flight);
    fused = FuseViews(*method, source, &geometry, FusionScope{}, timed_writer,
                      [clock] { clock->Mark("load + superpixels"); });
  }
  const double fusion_wall_s = clock->Mark("fusion").wall_s;
  summary->write_seconds = timed_writer.seconds();
  summary->superpixels_computed = fused.superpixels_computed;
  summary->superpixel_seconds = fused.load_seconds;
  spdlog::info("{} views loaded in {:.1f} s{}", views.size(), fused.load_seconds,
               superpixels ? fmt::format(" (superpixels: {} computed, {} reused from {})", fused.superpixels_computed,
                                         views.size() - fused.superpixels_computed, cache_dir)
                           : std::string());
  SetFusionSummary(fused.stats, summary);
  PauseAtTestPoint("run:before_commit");
  CheckInputsUnchanged(input, pinned);  // inputs pinned: the last step before the cloud is finished and renamed
  writer->Close();
  clock->Mark("write fused cloud");
  spdlog::info("{:.1f} s of the fusion stage's {:.1f} s were spent in the writer of {}", summary->write_seconds,
               fusion_wall_s, summary->las_path);
  summary->output_points = writer->num_points();
  // The DSM over the project area, the same extent a tiled run of the block has (the one-tile plan's area).
  if (const std::optional<DsmGrid> dsm = DsmGridOf(config, input, BuildTilePlan(input, config.tiling).grid.area())) {
    summary->dsm = MakeUntiledDsm(config, *dsm, summary->las_path);
    clock->Mark("DSM");
  } else {
    RemoveDsmFiles(config);
  }
  summary->ortho = MakeOrthoOfRun(config, input, summary->dsm,
                                  summary->dsm.written ? std::vector<OrthoCloud>{FusedCloud(summary->las_path)}
                                                       : std::vector<OrthoCloud>{});
  if (summary->ortho.written) clock->Mark("true ortho");
  for (size_t i = 0; i < views.size(); ++i) {
    const uint32_t v = views[i].index;
    summary->views[i].output_points = v < fused.points_per_view.size() ? fused.points_per_view[v] : 0;
  }
}

// Scores fused.las when evaluation.reference is set (DIR/eval.json; the table into summary->eval_text), then
// writes the HTML report once, with the scores. A scoring error is rethrown after the report (without scores).
// Marks "scoring" and "HTML report" on `clock`.
void ScoreAndReport(const JobConfig& config, StageClock* clock, RunSummary* summary) {
  const ReportOptions report = JobReportOptions(config);
  if (!config.evaluation.reference.empty()) {
    try {
      std::ostringstream table;
      RunEvaluation(EvalRequestFromConfig(config, summary->las_path, EvalJsonPath(config)), table);
      summary->eval_text = table.str();
    } catch (...) {
      WriteHtmlReportOrWarn(config, report);
      throw;
    }
    clock->Mark("scoring");
  }
  WriteHtmlReportOrWarn(config, report);  // DIR/report/index.html; a failure is only a warning
  clock->Mark("HTML report");
}

// The stage list and totals so far into the summary.
void RecordStages(const StageClock& clock, RunSummary* summary) {
  summary->stages = clock.stages();
  summary->total_wall_seconds = clock.TotalWallSeconds();
  summary->total_cpu_seconds = clock.TotalCpuSeconds();
}

}  // namespace

RunSummary RunFusionJob(const JobConfig& given, OutputWriterLock& lock, const RunProgress& progress,
                        const std::vector<std::string>& rerun_tiles) {
  ValidateJobConfig(given);
  JobConfig config = given;
  StageClock clock;
  std::filesystem::create_directories(config.output.dir);
  RemoveTemporaryFilesOfGoneProcesses(config, &lock);
  PauseAtTestPoint("run:started");

  RunSummary summary;
  summary.method = NameOf(config.fusion.method);
  summary.las_path = FusedLasPath(config);
  summary.effective_config_path = EffectiveConfigPath(config);
  summary.report_path = RunReportPath(config);
  WriteFileAtomically(summary.effective_config_path, DumpJobConfig(config, true));

  std::unique_ptr<DepthBlock> block = OpenNonEmptyInput(config.input, "fuse", config.crs);
  // The views' files as this run first sees them: checked again before the cloud is written (inputs pinned).
  const std::vector<ViewIdentity> pinned = IdentifyBlock(*block).views;
  clock.Mark("open input");
  TilingDecision decision;
  config = ResolveTiling(given, *block, &decision);
  clock.Mark("tiling decision");
  const ThreadLimit thread_limit(EffectiveThreads(config));
  // The superpixels' one-time tables are built on the pool beside co-registration (whose parallel loops take the
  // task up when a thread is free), not at the first view while the other threads wait for them.
  tbb::task_group tables;
  if (MakeFusionMethod(config.fusion)->needs().superpixels) tables.run([] { PrepareSuperpixelTables(); });
  block = WithCoregisteredPoses(config, std::move(block), &summary.coregistration);
  tables.wait();
  if (summary.coregistration.enabled) clock.Mark("co-registration");
  const DepthBlock& input = *block;
  const auto& views = input.views();
  summary.threads = EffectiveThreads(config);
  summary.tile_size_m = config.tiling.tile_size_m;
  summary.tiling_reason = decision.reason;
  summary.memory_budget_gib = config.resources.memory_gb;
  summary.memory_estimate_gib =
      static_cast<double>(decision.tiled ? decision.max_tile_bytes : decision.untiled_bytes) / kGiB;
  const bool tiled = config.tiling.tile_size_m > 0;  // every method
  if (!tiled) CheckRerunTiles(rerun_tiles, nullptr);
  if (given.tiling.tile_size_m != config.tiling.tile_size_m) {
    WriteFileAtomically(summary.effective_config_path, DumpJobConfig(config, true));  // with the size chosen
  }
  spdlog::info("input: {} views from {}", views.size(), config.input.path);
  summary.views.resize(views.size());
  for (size_t i = 0; i < views.size(); ++i) summary.views[i].name = views[i].name;
  if (config.fusion.method == FusionMethodKind::kSac) {
    spdlog::info("fusion method: sac (Select-and-Combine, unary '{}', correspondences '{}')",
                 config.fusion.sac.unary, config.fusion.sac.correspondence);
  } else if (config.fusion.method == FusionMethodKind::kUnion) {
    spdlog::info("fusion method: union (every valid depth pixel becomes a point; no fusion)");
  } else {
    spdlog::info("fusion method: {} (comparison method; no superpixels)", NameOf(config.fusion.method));
  }
  if (tiled) {
    RunTiled(config, input, progress, rerun_tiles, decision.views_in_flight, pinned, lock, &clock, &summary);
  } else {
    lock.Record(ResultSettingsHash(config), "");
    RunUntiled(config, input, progress, decision.views_in_flight, pinned, &clock, &summary);
  }

  summary.wall_seconds = clock.TotalWallSeconds();
  summary.cpu_seconds = clock.TotalCpuSeconds();
  summary.peak_rss_mib = PeakRssMiB();
  if (!summary.failed_tiles.empty()) return summary;  // the previous run's outputs stay (jobs/run_state.h)
  RemoveOtherFormatCloud(config);
  RecordStages(clock, &summary);
  WriteRunReport(summary, config);
  clock.Mark("run report");
  spdlog::info("wrote {} points to {} in {:.1f} s (peak RSS {:.0f} MiB)", summary.output_points, summary.las_path,
               summary.wall_seconds, summary.peak_rss_mib);
  try {
    ScoreAndReport(config, &clock, &summary);
  } catch (...) {
    RecordStages(clock, &summary);
    WriteRunReport(summary, config);  // with the stages up to the scoring error
    throw;
  }
  RecordStages(clock, &summary);
  WriteRunReport(summary, config);  // again, with the times of scoring and the HTML report
  spdlog::info("stages on {} threads:\n{}", summary.threads,
               FormatStageTable(summary.stages, summary.total_wall_seconds, summary.total_cpu_seconds));
  return summary;
}

}  // namespace sacfuse
