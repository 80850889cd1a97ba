#include "eval/eval_report_json.h"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "config/version.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

EvalReport Sample() {
  EvalReport r;
  ThresholdScore s;
  s.tau_m = 0.2;
  s.accuracy = 0.9;
  s.completeness = 0.8;
  s.f1 = 2 * 0.9 * 0.8 / 1.7;
  s.result_observed = 90;
  r.scores.push_back(s);
  r.result_points = 100;
  r.result_points_evaluated = 90;
  r.result_points_unobserved = 10;
  r.source_id_histogram = {{1, 60}, {7, 40}};
  r.aligned = true;
  r.alignment(0, 3) = 0.4;
  r.area_m2 = 12.5;
  return r;
}

TEST(EvalReportJsonTest, RoundTripsTheNumbers) {
  const auto j = nlohmann::json::parse(EvalReportToJson(Sample()));
  ASSERT_EQ(j["scores"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["scores"][0]["accuracy"].get<double>(), 0.9);
  EXPECT_DOUBLE_EQ(j["scores"][0]["tau_m"].get<double>(), 0.2);
  EXPECT_EQ(j["scores"][0]["result_observed"].get<uint64_t>(), 90u);
  EXPECT_EQ(j["result_points"].get<uint64_t>(), 100u);
  EXPECT_EQ(j["source_id_histogram"]["7"].get<uint64_t>(), 40u);
  EXPECT_TRUE(j["aligned"].get<bool>());
  EXPECT_DOUBLE_EQ(j["alignment"][0][3].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(j["alignment"][3][3].get<double>(), 1.0);
  EXPECT_EQ(j["version"].get<std::string>(), FullVersionString());  // which sacfuse scored
}

TEST(EvalReportJsonTest, WritesAFileAndTheTableShowsPercentages) {
  testing::TempDir dir;
  const std::string path = (dir / "sub" / "report.json").string();
  WriteEvalReportJson(Sample(), path);
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(nlohmann::json::parse(ss.str())["area_m2"].get<double>(), 12.5);
  const std::string table = FormatEvalTable(Sample());
  EXPECT_NE(table.find("90.00%"), std::string::npos) << table;
  EXPECT_NE(table.find("80.00%"), std::string::npos) << table;
  EXPECT_NE(table.find("0.200"), std::string::npos) << table;
  EXPECT_NE(table.find("7:40"), std::string::npos) << table;
  EXPECT_NE(table.find("alignment"), std::string::npos) << table;
}

}  // namespace
}  // namespace sacfuse
