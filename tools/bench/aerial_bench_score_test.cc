// Reading aerial-bench's results: a score.py --json-only line and a peers.json, hand-made with known answers.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/support/error_of.h"
#include "tools/bench/aerial_bench_score.h"

namespace sacfuse::bench {
namespace {

using nlohmann::json;

// score.py's fields (protocol v2) at GSD 0.25: tau 0.5 = 2 x GSD, 1.25 = 5 x GSD; listed out of order.
const char* const kScoreLine =
    R"({"protocol": "v2", "gsd": 0.25, "thresholds": [0.5, 1.25], "points_in_mask": 372000, )"
    R"("density_per_m2": 30.75, "scores": [{"tau": 1.25, "f1": 0.9985, "accuracy": 0.999}, )"
    R"({"tau": 0.5, "f1": 0.9752, "accuracy": 0.98}], "diagnostics_v2": {"tau": 0.5, "above_top": 0.0133}})";

TEST(AerialBenchScoreTest, ReadsTheScoreLineAfterWarnings) {
  const std::string text = std::string("UserWarning: something\n  warnings.warn(x)\n") + kScoreLine + "\n| table |\n";
  const AerialScore s = ParseScoreOutput(text, "score.log");
  EXPECT_DOUBLE_EQ(s.f1_2gsd, 0.9752);
  EXPECT_DOUBLE_EQ(s.f1_5gsd, 0.9985);
  EXPECT_DOUBLE_EQ(s.points_in_mask, 372000);
  EXPECT_DOUBLE_EQ(s.density_per_m2, 30.75);
  EXPECT_DOUBLE_EQ(s.above_top, 0.0133);
}

TEST(AerialBenchScoreTest, OwnJsonFormReadsBack) {
  const AerialScore s = ParseScoreOutput(kScoreLine, "x");
  const AerialScore t = AerialScoreFromJson(AerialScoreToJson(s), "row.json");
  EXPECT_DOUBLE_EQ(t.f1_2gsd, s.f1_2gsd);
  EXPECT_DOUBLE_EQ(t.f1_5gsd, s.f1_5gsd);
  EXPECT_DOUBLE_EQ(t.points_in_mask, s.points_in_mask);
  EXPECT_DOUBLE_EQ(t.density_per_m2, s.density_per_m2);
  EXPECT_DOUBLE_EQ(t.above_top, s.above_top);
}

TEST(AerialBenchScoreTest, MissingLineOrThresholdNamesTheSource) {
  EXPECT_NE(testing::InputErrorOf([] { ParseScoreOutput("Traceback ...\nValueError\n", "score.log"); })
                .find("score.log: no JSON line from score.py"),
            std::string::npos);
  json j = json::parse(kScoreLine);
  j["gsd"] = 0.2;  // neither tau is 2 or 5 x GSD now
  EXPECT_NE(testing::InputErrorOf([&] { AerialScoreFromJson(j, "s.json"); }).find("no score at 2 and 5 x GSD"),
            std::string::npos);
  j = json::parse(kScoreLine);
  j.erase("diagnostics_v2");
  EXPECT_NE(testing::InputErrorOf([&] { AerialScoreFromJson(j, "s.json"); }).find("s.json"), std::string::npos);
}

TEST(AerialBenchScoreTest, ReadsPeersJsonRowsAndFailures) {
  json peers = {{"gsd", 0.25}, {"peers", json::array()}};
  json tsdf = {{"method", "tsdf"}, {"returncode", 0}, {"wall_s", 48.06}, {"peak_rss_mb", 3556.0},
               {"score", json::parse(kScoreLine)}};
  tsdf["score"]["points_in_mask"] = 567906;
  json oracle = {{"method", "oracle"}, {"reference_only", true}, {"returncode", 0}, {"wall_s", nullptr},
                 {"peak_rss_mb", nullptr}, {"score", json::parse(kScoreLine)}};
  json colmap = {{"method", "colmap_best"}, {"returncode", 1}, {"wall_s", nullptr}, {"peak_rss_mb", nullptr}};
  peers["peers"] = {tsdf, oracle, colmap};
  const auto rows = ParsePeersJson(peers, "peers.json");
  ASSERT_EQ(rows.size(), 3u);
  const AerialPeer& t = rows.at("tsdf");
  EXPECT_TRUE(t.ok);
  EXPECT_DOUBLE_EQ(t.wall_s, 48.06);
  EXPECT_DOUBLE_EQ(t.peak_rss_mib, 3556.0);
  EXPECT_DOUBLE_EQ(t.score.points_in_mask, 567906);
  EXPECT_DOUBLE_EQ(t.score.f1_2gsd, 0.9752);
  EXPECT_TRUE(rows.at("oracle").ok);
  EXPECT_TRUE(std::isnan(rows.at("oracle").wall_s));
  EXPECT_FALSE(rows.at("colmap_best").ok);
  EXPECT_NE(rows.at("colmap_best").error.find("returncode 1"), std::string::npos);
  EXPECT_NE(testing::InputErrorOf([] { ParsePeersJson(json::object(), "p.json"); }).find("p.json: no \"peers\""),
            std::string::npos);
}

}  // namespace
}  // namespace sacfuse::bench
