// The table maths of `sacfuse bench` on hand-made rows with known answers: gap closed, rank, redundancy, group
// summaries, averages over blocks; and reading an eval.json into a row.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/test_support.h"
#include "tools/bench/quality_bench_table.h"
#include "eval/eval_report_json.h"

namespace sacfuse::bench {
namespace {

BenchRow Row(const std::string& scene, double scale, const std::string& name, double f1_2, double f1_5,
             uint64_t points = 1000) {
  BenchRow r;
  r.spec.section = "main";
  r.spec.scene = scene;
  r.spec.error_scale = scale;
  r.spec.name = name;
  r.spec.is_sac = name == "sac";
  r.spec.is_ceiling = name == "ceiling";
  r.result.status = "ok";
  r.result.metrics.f1_2gsd_pct = f1_2;
  r.result.metrics.f1_5gsd_pct = f1_5;
  r.result.metrics.points = points;
  r.result.metrics.wall_s = 10.0;
  return r;
}

BenchRow Failed(const std::string& scene, double scale, const std::string& name) {
  BenchRow r = Row(scene, scale, name, 99.0, 99.0);
  r.result.status = "failed";
  r.result.error = "boom";
  return r;
}

TEST(QualityBenchTableTest, GapClosedIsTheShareOfTheGapToTheCeiling) {
  EXPECT_DOUBLE_EQ(GapClosed(70.0, 60.0, 100.0), 0.25);
  EXPECT_DOUBLE_EQ(GapClosed(100.0, 60.0, 100.0), 1.0);
  EXPECT_DOUBLE_EQ(GapClosed(60.0, 60.0, 100.0), 0.0);
  EXPECT_DOUBLE_EQ(GapClosed(50.0, 60.0, 100.0), -0.25);  // worse than the best other method
  EXPECT_TRUE(std::isnan(GapClosed(70.0, 80.0, 80.0)));   // no gap to close
  EXPECT_TRUE(std::isnan(GapClosed(70.0, 90.0, 80.0)));
  EXPECT_TRUE(std::isnan(GapClosed(kNoValue, 60.0, 100.0)));
  EXPECT_TRUE(std::isnan(GapClosed(70.0, 60.0, kNoValue)));
}

TEST(QualityBenchTableTest, RankCountsStrictlyBetterValuesAndSharesTies) {
  EXPECT_EQ(RankOf(66.0, {66.0, 83.0, 63.0, 65.0}), 2);
  EXPECT_EQ(RankOf(83.0, {66.0, 83.0, 63.0}), 1);
  EXPECT_EQ(RankOf(63.0, {66.0, 83.0, 63.0}), 3);
  EXPECT_EQ(RankOf(5.0, {5.0, 5.0, 3.0}), 1);
  EXPECT_EQ(RankOf(3.0, {5.0, 5.0, 3.0}), 3);
  EXPECT_EQ(RankOf(3.0, {kNoValue, 5.0, 3.0}), 2);  // NaN is not better
}

TEST(QualityBenchTableTest, RedundancyIsPointsPerGsdCell) {
  EXPECT_DOUBLE_EQ(Redundancy(1000.0, 10.0, 0.1), 1.0);  // 10 m2 = 1000 cells of 10 cm
  EXPECT_DOUBLE_EQ(Redundancy(5000.0, 10.0, 0.1), 5.0);
  EXPECT_DOUBLE_EQ(Redundancy(250.0, 10.0, 0.2), 1.0);   // 250 cells of 20 cm
  EXPECT_TRUE(std::isnan(Redundancy(10.0, 0.0, 0.1)));
  EXPECT_TRUE(std::isnan(Redundancy(10.0, 10.0, 0.0)));
}

TEST(QualityBenchTableTest, GroupSummaryRanksSacAndFindsTheBestOtherAndTheCeiling) {
  const std::vector<BenchRow> rows = {
      Row("city", 1, "sac", 66.0, 99.2),     Row("city", 1, "union", 57.0, 95.8),
      Row("city", 1, "tsdf", 83.0, 98.4),    Failed("city", 1, "consistency"),
      Row("city", 1, "ceiling", 99.0, 100.0),
      Row("zurich", 1, "sac", 88.0, 99.8),   Row("zurich", 1, "union", 80.0, 97.8),
      Row("zurich", 1, "ceiling", 96.0, 100.0),
  };
  const std::vector<GroupSummary> g = SummariseGroups(rows);
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[0].scene, "city");
  EXPECT_EQ(g[0].ranked, 3);  // failed and ceiling rows are not ranked
  EXPECT_EQ(g[0].sac_rank_2gsd, 2);
  EXPECT_EQ(g[0].sac_rank_5gsd, 1);
  EXPECT_EQ(g[0].best_other, "tsdf");
  EXPECT_DOUBLE_EQ(g[0].best_other_f1_2gsd, 83.0);
  EXPECT_DOUBLE_EQ(g[0].ceiling_f1_2gsd, 99.0);
  EXPECT_DOUBLE_EQ(g[0].gap_closed, (66.0 - 83.0) / (99.0 - 83.0));
  EXPECT_EQ(g[1].scene, "zurich");
  EXPECT_EQ(g[1].sac_rank_2gsd, 1);
  EXPECT_EQ(g[1].best_other, "union");
  EXPECT_DOUBLE_EQ(g[1].gap_closed, 0.5);  // (88 - 80) / (96 - 80)
}

TEST(QualityBenchTableTest, GroupWithoutSacOrCeilingHasNoRankAndNoGap) {
  const std::vector<GroupSummary> g =
      SummariseGroups({Row("city", 1, "union", 57.0, 95.8), Failed("city", 1, "sac")});
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].sac_rank_2gsd, 0);
  EXPECT_TRUE(std::isnan(g[0].gap_closed));
}

TEST(QualityBenchTableTest, AveragesAreMeansOverTheBlocksWhereARowRan) {
  std::vector<BenchRow> rows = {
      Row("city", 1, "sac", 60.0, 99.0, 100),  Row("city", 1, "union", 50.0, 95.0, 300),
      Row("city", 1, "ceiling", 100.0, 100.0), Row("zurich", 1, "sac", 70.0, 97.0, 200),
      Failed("zurich", 1, "union"),            Row("zurich", 1, "ceiling", 90.0, 100.0),
      Row("city", 2.5, "sac", 40.0, 90.0),     Row("city", 2.5, "union", 45.0, 91.0),
      Row("city", 2.5, "ceiling", 100.0, 100.0),
  };
  rows[0].result.metrics.wall_s = 4.0;
  rows[3].result.metrics.wall_s = kNoValue;  // a missing value leaves its column's mean alone
  const std::vector<GroupSummary> summaries = SummariseGroups(rows);
  const std::vector<ScaleAverage> a = AverageOverBlocks(rows, summaries);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].error_scale, 1.0);
  EXPECT_EQ(a[0].scenes, (std::vector<std::string>{"city", "zurich"}));
  ASSERT_EQ(a[0].rows.size(), 3u);
  EXPECT_EQ(a[0].rows[0].name, "sac");
  EXPECT_EQ(a[0].rows[0].blocks, 2);
  EXPECT_DOUBLE_EQ(a[0].rows[0].mean.f1_2gsd_pct, 65.0);
  EXPECT_DOUBLE_EQ(a[0].rows[0].mean.f1_5gsd_pct, 98.0);
  EXPECT_EQ(a[0].rows[0].mean.points, 150u);
  EXPECT_DOUBLE_EQ(a[0].rows[0].mean.wall_s, 4.0);
  EXPECT_EQ(a[0].rows[1].name, "union");
  EXPECT_EQ(a[0].rows[1].blocks, 1);  // failed on zurich
  EXPECT_DOUBLE_EQ(a[0].rows[1].mean.f1_2gsd_pct, 50.0);
  EXPECT_EQ(a[0].rows[2].name, "ceiling");
  EXPECT_DOUBLE_EQ(a[0].rows[2].mean.f1_2gsd_pct, 95.0);
  // city: (60 - 50) / (100 - 50) = 0.2; zurich: no other successful row, so no gap.
  EXPECT_DOUBLE_EQ(a[0].gap_closed, 0.2);
  EXPECT_DOUBLE_EQ(a[0].sac_rank_2gsd, 1.0);
  EXPECT_EQ(a[1].error_scale, 2.5);
  EXPECT_DOUBLE_EQ(a[1].sac_rank_2gsd, 2.0);
  EXPECT_DOUBLE_EQ(a[1].sac_rank_5gsd, 2.0);
  EXPECT_DOUBLE_EQ(a[1].gap_closed, (40.0 - 45.0) / (100.0 - 45.0));
}

TEST(QualityBenchTableTest, AblationRowsAreNotAveraged) {
  BenchRow r = Row("city", 1, "sac", 60.0, 99.0);
  r.spec.section = "ablation";
  const auto summaries = SummariseGroups({r});
  ASSERT_EQ(summaries.size(), 1u);
  EXPECT_EQ(summaries[0].section, "ablation");
  EXPECT_TRUE(AverageOverBlocks({r}, summaries).empty());
}

TEST(QualityBenchResultTest, MetricsFromAnEvalJson) {
  testing::TempDir dir;
  EvalReport report;
  ThresholdScore s2, s5, s10;
  s2.tau_m = 0.2;
  s2.f1 = 0.6655;
  s2.accuracy = 0.5074;
  s2.completeness = 0.9666;
  s5.tau_m = 0.5;
  s5.f1 = 0.9923;
  s10.tau_m = 1.0;
  s10.f1 = 1.0;
  report.scores = {s2, s5, s10};
  report.mean_abs_distance_m = 0.123;
  report.result_points = 5000;  // scored: every 2nd point of the file
  report.result_stride = 2;
  report.result_points_in_file = 10000;
  report.result_points_outside_mask = 1000;
  report.area_m2 = 40.0;
  const std::string path = (dir / "eval.json").string();
  WriteEvalReportJson(report, path);
  const RowMetrics m = MetricsFromEvalJson(path, 0.1);
  EXPECT_NEAR(m.f1_2gsd_pct, 66.55, 1e-9);
  EXPECT_NEAR(m.f1_5gsd_pct, 99.23, 1e-9);
  EXPECT_NEAR(m.accuracy_2gsd_pct, 50.74, 1e-9);
  EXPECT_NEAR(m.completeness_2gsd_pct, 96.66, 1e-9);
  EXPECT_DOUBLE_EQ(m.mean_abs_distance_m, 0.123);
  EXPECT_EQ(m.points, 10000u);
  // (5000 - 1000) scored points in the mask x stride 2 over 40 m2 = 4000 cells of 10 cm.
  EXPECT_DOUBLE_EQ(m.redundancy, 2.0);

  // Scored at 0.2 m with a 0.2 m GSD there is no 2 x GSD threshold.
  const std::string error = testing::InputErrorOf([&] { MetricsFromEvalJson(path, 0.2); });
  EXPECT_NE(error.find("2 and 5 x GSD"), std::string::npos) << error;
  EXPECT_NE(testing::InputErrorOf([&] { MetricsFromEvalJson((dir / "none.json").string(), 0.1); }).find("none.json"),
            std::string::npos);
}

TEST(QualityBenchResultTest, RowJsonRoundTripKeepsMissingValuesMissing) {
  RowResult r;
  r.status = "ok";
  r.key = "k";
  r.metrics.f1_2gsd_pct = 12.5;
  r.metrics.points = 42;
  r.eval_s = 1.5;
  const nlohmann::json j = RowResultToJson(r);
  EXPECT_TRUE(j["f1_5gsd_pct"].is_null());
  const RowResult back = RowResultFromJson(j);
  EXPECT_TRUE(back.ok());
  EXPECT_EQ(back.key, "k");
  EXPECT_DOUBLE_EQ(back.metrics.f1_2gsd_pct, 12.5);
  EXPECT_TRUE(std::isnan(back.metrics.f1_5gsd_pct));
  EXPECT_EQ(back.metrics.points, 42u);
  EXPECT_DOUBLE_EQ(back.eval_s, 1.5);
}

}  // namespace
}  // namespace sacfuse::bench
