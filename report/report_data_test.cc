// Gathering the report's data from a run folder: the JSON files, stale scores, tile states, and no throwing on
// missing or corrupt files (a warning instead).
#include "report/report_data.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "config/result_settings.h"
#include "io/las_writer.h"
#include "tiles/tile_marker.h"
#include "config/output_layout.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {
namespace fs = std::filesystem;

const char* kRunReport = R"({"version": "sacfuse 0.1.0", "method": "sac", "config": "/x/job.yaml",
  "input_points": 3000, "output_points": 1200, "wall_seconds": 12.5, "cpu_seconds": 20.0, "peak_rss_mib": 321.0,
  "threads": 2, "memory": {"budget_gib": 4.0, "estimate_gib": 0.5},
  "tiling_decision": {"tile_size_m": 0.0, "reason": "untiled: fits"},
  "stage_wall_seconds": {"superpixels": 1.5, "tiles": 0.0, "merge": 0.0},
  "views": [{"name": "nadir/a.jpg", "input_pixels": 2000, "output_points": 1000},
            {"name": "oblique_fwd/b.jpg", "input_pixels": 1000, "output_points": 200}],
  "sac": {"valid_nodes": 50, "netlets": 50, "nodes_relabelled": 7, "pixels_collapsed": 1500,
          "pixels_kept_uncovered": 100, "pixels_outliers": 300}})";

const char* kEval = R"({"scores": [{"tau_m": 0.2, "accuracy": 0.8, "completeness": 0.9, "f1": 0.847},
                                   {"tau_m": 0.5, "accuracy": 0.95, "completeness": 0.99, "f1": 0.97}],
  "mean_abs_distance_m": 0.12, "median_abs_distance_m": 0.08, "result_points_evaluated": 1200,
  "reference_points_evaluated": 400, "result_stride": 1, "aligned": false})";

void Write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

void WriteCloud(const fs::path& path) {
  LasWriter w(path.string(), LasWriterOptions{});
  FusedPoint p;
  p.point_in_world = {10.0, 20.0, 30.0};
  w.Write(&p, 1);
  p.point_in_world = {14.0, 25.0, 31.0};
  w.Write(&p, 1);
  w.Close();
}

TEST(ReportDataTest, ParsesTheRunReport) {
  const ReportRun r = ParseRunReportJson(kRunReport);
  EXPECT_TRUE(r.present);
  EXPECT_EQ(r.method, "sac");
  EXPECT_EQ(r.input_points, 3000u);
  EXPECT_EQ(r.output_points, 1200u);
  ASSERT_EQ(r.views.size(), 2u);
  EXPECT_EQ(r.views[1].view, 1u);
  EXPECT_EQ(r.views[1].name, "oblique_fwd/b.jpg");
  EXPECT_EQ(r.views[1].before, 1000u);
  EXPECT_EQ(r.views[1].after, 200u);
  EXPECT_TRUE(r.has_sac);
  EXPECT_EQ(r.sac_pixels_outliers, 300u);
  EXPECT_DOUBLE_EQ(r.superpixel_seconds, 1.5);
  EXPECT_THROW(ParseRunReportJson("{not json"), std::exception);
}

TEST(ReportDataTest, ParsesScores) {
  const ReportEval e = ParseEvalJson(kEval);
  ASSERT_EQ(e.scores.size(), 2u);
  EXPECT_DOUBLE_EQ(e.scores[0].tau_m, 0.2);
  EXPECT_DOUBLE_EQ(e.scores[1].f1, 0.97);
  EXPECT_DOUBLE_EQ(e.median_abs_distance_m, 0.08);
  EXPECT_THROW(ParseEvalJson("{\"scores\": [{\"tau_m\": 1}]}"), std::exception);
}

TEST(ReportDataTest, ScoresOlderThanTheCloudAreNotShown) {
  testing::TempDir dir;
  JobConfig config;
  config.output.dir = dir.path().string();
  Write(dir / "run_report.json", kRunReport);
  Write(dir / "eval.json", kEval);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  WriteCloud(dir / "fused.laz");  // newer than eval.json
  ReportData d = GatherReportData(config);
  EXPECT_TRUE(d.cloud.exists);
  EXPECT_EQ(d.cloud.points, 2u);
  EXPECT_DOUBLE_EQ(d.cloud.max[1], 25.0);
  EXPECT_TRUE(d.eval.stale);
  EXPECT_FALSE(d.eval.present);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  Write(dir / "eval.json", kEval);  // rescored
  d = GatherReportData(config);
  EXPECT_FALSE(d.eval.stale);
  ASSERT_TRUE(d.eval.present);
  EXPECT_EQ(d.eval.scores.size(), 2u);
  EXPECT_FALSE(d.tiled);
  EXPECT_TRUE(d.warnings.size() == 1 && d.warnings[0].find("sacfuse.effective.yaml") != std::string::npos);
}

TEST(ReportDataTest, MissingOrCorruptFilesGiveWarningsNotExceptions) {
  testing::TempDir dir;
  JobConfig config;
  config.output.dir = dir.path().string();
  ReportData d = GatherReportData(config);  // an empty folder
  EXPECT_FALSE(d.run.present);
  EXPECT_FALSE(d.cloud.exists);
  EXPECT_GE(d.warnings.size(), 2u);
  Write(dir / "run_report.json", "{\"views\": [1, 2");  // truncated
  Write(dir / "eval.json", "garbage");
  Write(dir / "fused.laz", "LASF but not really");
  d = GatherReportData(config);
  EXPECT_FALSE(d.run.present);
  EXPECT_FALSE(d.eval.present);
  EXPECT_FALSE(d.cloud.exists);
  std::string all;
  for (const auto& w : d.warnings) all += w + "\n";
  EXPECT_NE(all.find("run_report.json unreadable"), std::string::npos) << all;
  EXPECT_NE(all.find("eval.json unreadable"), std::string::npos) << all;
  EXPECT_NE(all.find("fused.laz unreadable"), std::string::npos) << all;
}

TEST(ReportDataTest, TileStatesComeFromTheMarkers) {
  testing::TempDir dir;
  JobConfig config;
  config.output.dir = dir.path().string();
  const std::string tiles_dir = TilesDir(config);
  Write(fs::path(tiles_dir) / "manifest.json",
        R"({"config_hash": "x", "tile_size_m": 20.0, "tiles": ["0_0", "1_0", "0_1"]})");
  Write(dir / "plan.json", R"({"tiles": [{"id": "0_0", "core": [0, 0, 20, 20], "memory_bytes": 1048576},
                                         {"id": "1_0", "core": [20, 0, 40, 20], "memory_bytes": 0},
                                         {"id": "0_1", "core": [0, 20, 20, 40], "memory_bytes": 0}]})");
  JobConfig resolved = config;
  resolved.tiling.tile_size_m = 20.0;  // the hash of the run as it ran (automatic size resolved)
  TileDoneMarker done;
  done.id = "0_0";
  done.config_hash = ResultSettingsHash(resolved);
  done.views = 3;
  done.seconds = 1.25;
  done.peak_rss_mib = 99.0;
  WriteTileDoneMarker(tiles_dir, done);  // an empty tile: no LAS file needed
  WriteTileFailedMarker(tiles_dir, "1_0", "out-of-memory guard");
  Write(dir / "run_report.json", R"({"tiling_decision": {"tile_size_m": 20.0}, "views": []})");

  const ReportData d = GatherReportData(config);
  EXPECT_EQ(d.warnings.size(), 1u);  // no sacfuse.effective.yaml
  ASSERT_TRUE(d.tiled);
  ASSERT_EQ(d.tiles.size(), 3u);
  EXPECT_EQ(d.tiles[0].status, TileStatus::kDone);
  EXPECT_DOUBLE_EQ(d.tiles[0].seconds, 1.25);
  EXPECT_EQ(d.tiles[0].views, 3u);
  EXPECT_EQ(d.tiles[0].memory_estimate_bytes, 1048576u);
  EXPECT_TRUE(d.tiles[0].has_core);
  EXPECT_DOUBLE_EQ(d.tiles[1].core.min.x(), 20.0);
  EXPECT_EQ(d.tiles[1].status, TileStatus::kFailed);
  EXPECT_EQ(d.tiles[1].reason, "out-of-memory guard");
  EXPECT_EQ(d.tiles[2].status, TileStatus::kPending);
  EXPECT_EQ(d.tiles[2].ix, 0);
  EXPECT_EQ(d.tiles[2].iy, 1);

  // A done marker of another config does not count as done.
  done.config_hash = "0000000000000000";
  WriteTileDoneMarker(tiles_dir, done);
  EXPECT_EQ(GatherReportData(config).tiles[0].status, TileStatus::kPending);
}

}  // namespace
}  // namespace sacfuse
