// The aerial-bench table on hand-made rows with known answers: ratio to TSDF's points, SAC's rank (oracle
// excluded), half-way from the best peer to the oracle, the Markdown table and its JSON.
#include <cmath>

#include <gtest/gtest.h>

#include "tools/bench/aerial_bench_format.h"
#include "tools/bench/aerial_bench_table.h"

namespace sacfuse::bench {
namespace {

AerialRow Row(const std::string& block, const std::string& method, double f1_2, double f1_5, double points) {
  AerialRow r;
  r.block = block;
  r.method = method;
  r.result.status = "ok";
  r.result.metrics.wall_s = 12.34;
  r.result.metrics.peak_rss_mib = 812.4;
  r.score.f1_2gsd = f1_2;
  r.score.f1_5gsd = f1_5;
  r.score.points_in_mask = points;
  r.score.density_per_m2 = points / 10000.0;
  r.score.above_top = 0.0133;
  return r;
}

// Block a: SAC 0.97 between TSDF 0.96 and the oracle 0.98 (exactly half-way); second at 5 x GSD behind union.
std::vector<AerialRow> BlockA() {
  return {Row("a", "sacfuse", 0.97, 0.995, 200000), Row("a", "tsdf", 0.96, 0.996, 400000),
          Row("a", "union", 0.90, 0.998, 4000000), Row("a", "oracle", 0.98, 0.999, 5000000)};
}

TEST(AerialBenchTableTest, RatioToTsdfIsPointsInMaskOverTsdfs) {
  std::vector<AerialRow> rows = BlockA();
  EXPECT_DOUBLE_EQ(RatioToTsdf(rows[0], rows), 0.5);
  EXPECT_DOUBLE_EQ(RatioToTsdf(rows[1], rows), 1.0);
  EXPECT_DOUBLE_EQ(RatioToTsdf(rows[2], rows), 10.0);
  std::vector<AerialRow> no_tsdf = {rows[0], rows[2]};
  EXPECT_TRUE(std::isnan(RatioToTsdf(no_tsdf[0], no_tsdf)));
  rows[1].result.status = "failed";
  EXPECT_TRUE(std::isnan(RatioToTsdf(rows[0], rows)));
}

TEST(AerialBenchTableTest, RankExcludesTheOracleAndHalfWayIsGapClosedAtLeastHalf) {
  const std::vector<AerialSummary> s = SummariseAerial(BlockA());
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].ranked, 3);
  EXPECT_EQ(s[0].sac_rank_2gsd, 1);
  EXPECT_EQ(s[0].sac_rank_5gsd, 3);  // tsdf 0.996 and union 0.998 are above 0.995
  EXPECT_EQ(s[0].best_peer, "tsdf");
  EXPECT_DOUBLE_EQ(s[0].oracle_f1_2gsd, 0.98);
  EXPECT_NEAR(s[0].gap_closed, 0.5, 1e-12);
  EXPECT_TRUE(s[0].half_way);
}

TEST(AerialBenchTableTest, BlocksAreSummarisedApartAndFailedRowsAreNotRanked) {
  std::vector<AerialRow> rows = BlockA();
  rows.push_back(Row("b", "sacfuse", 0.88, 0.99, 100));
  rows.push_back(Row("b", "colmap_best", 0.87, 0.99, 100));
  rows.push_back(Row("b", "tsdf", 0.69, 0.97, 100));
  AerialRow failed = Row("b", "union", 0.99, 0.99, 100);
  failed.result.status = "failed";
  rows.push_back(failed);
  rows.push_back(Row("b", "oracle", 0.97, 0.999, 100));
  const std::vector<AerialSummary> s = SummariseAerial(rows);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[1].block, "b");
  EXPECT_EQ(s[1].ranked, 3);
  EXPECT_EQ(s[1].sac_rank_2gsd, 1);
  EXPECT_EQ(s[1].sac_rank_5gsd, 1);  // ties share the rank
  EXPECT_EQ(s[1].best_peer, "colmap_best");
  EXPECT_NEAR(s[1].gap_closed, 0.1, 1e-12);  // (0.88 - 0.87) / (0.97 - 0.87)
  EXPECT_FALSE(s[1].half_way);
  rows[0].result.status = "failed";  // no SAC row on a
  const AerialSummary a = SummariseAerial(rows)[0];
  EXPECT_EQ(a.sac_rank_2gsd, 0);
  EXPECT_FALSE(a.half_way);
}

TEST(AerialBenchTableTest, MarkdownTableHasEveryRowAndTheBlockLine) {
  std::vector<AerialRow> rows = BlockA();
  rows[1].result.reused = true;
  rows.push_back(Row("b", "sacfuse", 0.5, 0.5, 1));
  rows.back().result.status = "failed";
  // DSM scores on a's sacfuse and TSDF rows (score_dsm.py of the DSMs, and of the clouds by its own p90 rule).
  const auto dsm = [](double nmad, double completeness) {
    AerialDsmScore d;
    d.nmad_m = nmad;
    d.completeness = completeness;
    d.median_m = 0.0;
    d.rmse_m = 1.0;
    return d;
  };
  rows[0].dsm = dsm(0.138, 0.9992);
  rows[0].dsm_p90 = dsm(0.156, 0.9975);
  rows[1].dsm = dsm(0.171, 0.9975);
  const std::string md = FormatAerialMarkdown(rows, SummariseAerial(rows));
  EXPECT_NE(md.find("| block | method | F1 2×GSD | F1 5×GSD | DSM NMAD m | DSM compl. % | p90 NMAD m | p90 compl. % | "
                    "points in mask /m² | × TSDF's points | above top % | wall s | peak RSS MiB |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| a | **sacfuse** | 0.9700 | 0.9950 | 0.138 | 99.92 | 0.156 | 99.75 | 20.0 | 0.50 | 1.33 | 12.3 | "
                    "812 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| a | Open3D TSDF ↺ | 0.9600 | 0.9960 | 0.171 | 99.75 |  |  | 40.0 | 1.00 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("DSM: NMAD 0.138 m (best peer 0.171), completeness 99.92 % (best peer 99.75): ahead on both."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| a | oracle | 0.9800 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| b | **sacfuse** | failed |"), std::string::npos) << md;
  EXPECT_NE(md.find("- a: SAC rank 1 of 3 at 2×GSD, 3 of 3 at 5×GSD; half-way to the oracle at 2×GSD: reached "
                    "(gap closed 50.0 %: best peer Open3D TSDF 0.9600, oracle 0.9800, SAC 0.9700)."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- b: no successful sacfuse row."), std::string::npos) << md;
  EXPECT_EQ(FormatAerialMarkdown({}, {}), "");
}

TEST(AerialBenchTableTest, JsonRowsCarryTheScoresAndTheRatio) {
  const std::vector<AerialRow> rows = BlockA();
  const nlohmann::json j = AerialRowsToJson(rows);
  ASSERT_EQ(j.size(), 4u);
  EXPECT_EQ(j[0]["method"], "sacfuse");
  EXPECT_EQ(j[0]["block"], "a");
  EXPECT_DOUBLE_EQ(j[0]["aerial"]["f1_2gsd"].get<double>(), 0.97);
  EXPECT_DOUBLE_EQ(j[0]["ratio_to_tsdf_points"].get<double>(), 0.5);
  EXPECT_FALSE(j[0].contains("key"));
  EXPECT_FALSE(j[0].contains("points")) << "no column of our own scorer";
  EXPECT_DOUBLE_EQ(j[0]["wall_s"].get<double>(), 12.34);
  const nlohmann::json s = AerialSummariesToJson(SummariseAerial(rows));
  EXPECT_EQ(s[0]["half_way"], true);
  EXPECT_EQ(s[0]["sac_rank_5gsd"], 3);
}

}  // namespace
}  // namespace sacfuse::bench
