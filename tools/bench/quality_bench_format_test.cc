// bench.md and bench.json of `sacfuse bench` from hand-made rows: columns, number formats, summaries, failed and
// skipped entries.
#include <cmath>

#include <gtest/gtest.h>

#include "tools/bench/quality_bench_format.h"

namespace sacfuse::bench {
namespace {

BenchRow Row(const std::string& section, const std::string& name, double f1_2, double f1_5, uint64_t points) {
  BenchRow r;
  r.spec.section = section;
  r.spec.scene = "city";
  r.spec.error_scale = 1.0;
  r.spec.name = name;
  r.spec.block_id = name == "ceiling" ? "city-small-seed7-noerrors" : "city-small-seed7-e1";
  r.spec.is_sac = name == "sac";
  r.spec.is_ceiling = name == "ceiling";
  r.result.status = "ok";
  RowMetrics& m = r.result.metrics;
  m.f1_2gsd_pct = f1_2;
  m.f1_5gsd_pct = f1_5;
  m.accuracy_2gsd_pct = 50.7449;
  m.completeness_2gsd_pct = 96.6612;
  m.mean_abs_distance_m = 0.12345;
  m.points = points;
  m.redundancy = 7.8123;
  m.wall_s = 9.04;
  m.peak_rss_mib = 384.4;
  if (name == "sac") {  // sacfuse rows score their DSM (eval.json "dsm"); the others have none
    m.dsm_nmad_m = 0.1384;
    m.dsm_completeness_pct = 99.916;
  }
  return r;
}

BenchDocument Document() {
  BenchDocument d;
  d.header.command_line = "sacfuse bench --out X";
  d.header.date = "2026-11-21 12:00:00 UTC";
  d.header.machine = "2 cores, 23.4 GiB RAM, Test CPU";
  d.header.sacfuse_version = "sacfuse 0.1.0";
  d.header.colmap_note = "not run (--colmap off)";
  BlockSpec b;
  b.id = "city-small-seed7-e1";
  b.scene = "city";
  b.preset = "small";
  d.blocks = {b};
  d.skipped = {{"zurich", "LiDAR file not found: /nowhere/lastools/zurich.las"}};
  d.rows = {Row("main", "sac", 66.554, 99.231, 10165096), Row("main", "union", 57.07, 95.77, 26082080),
            Row("main", "tsdf", 83.59, 98.44, 12305632), Row("main", "ceiling", 99.8, 100.0, 30000000),
            Row("ablation", "sac", 88.47, 99.95, 593269), Row("ablation", "sac, fusion.unary: paper", 0, 0, 0)};
  BlockSpec harsh = b;
  harsh.id = "city-small-seed7-e2.5";
  harsh.error_scale = 2.5;
  d.blocks.push_back(harsh);
  BenchRow harsh_sac = Row("main", "sac", 40.0, 90.0, 100);
  harsh_sac.spec.error_scale = 2.5;
  harsh_sac.spec.block_id = harsh.id;
  d.rows.insert(d.rows.begin() + 4, harsh_sac);
  d.rows[2].result.reused = true;
  d.rows[6].result = RowResult();
  d.rows[6].result.error = "config key rejected\nsecond line";
  Summarise(&d);
  return d;
}

TEST(QualityBenchFormatTest, NumberFormats) {
  EXPECT_EQ(FormatCount(0), "0");
  EXPECT_EQ(FormatCount(999), "999");
  EXPECT_EQ(FormatCount(1000), "1,000");
  EXPECT_EQ(FormatCount(26082080), "26,082,080");
  EXPECT_EQ(FormatFixed(66.554, 2), "66.55");
  EXPECT_EQ(FormatFixed(384.6, 0), "385");
  EXPECT_EQ(FormatFixed(std::nan(""), 2), "–");
}

TEST(QualityBenchFormatTest, MarkdownHasHeaderTablesSummariesAndFailures) {
  const std::string md = FormatBenchMarkdown(Document());
  for (const char* expected :
       {"command: `sacfuse bench --out X`", "machine: 2 cores, 23.4 GiB RAM, Test CPU", "sacfuse: sacfuse 0.1.0",
        "COLMAP: not run (--colmap off)", "skipped block zurich: LiDAR file not found: /nowhere/lastools/zurich.las",
        "## Error scale 1", "### city (procedural city, preset small, seed 7; block `city-small-seed7-e1`",
        "| method | F1 2×GSD % | F1 5×GSD % | accuracy 2× % | completeness 2× % | mean abs dist m | points | "
        "redundancy | DSM NMAD m | DSM compl. % | wall s | peak RSS MiB |",
        "| **sac** | 66.55 | 99.23 | 50.74 | 96.66 | 0.123 | 10,165,096 | 7.81 | 0.138 | 99.92 | 9.0 | 384 |",
        "| tsdf ↺ | 83.59 | 98.44 | 50.74 | 96.66 | 0.123 | 12,305,632 | 7.81 | – | – | 9.0 | 384 |",
        "| tsdf ↺ | 83.59 |", "| ceiling | 99.80 | 100.00 |",
        "SAC: rank 2 of 3 at 2×GSD, 1 of 3 at 5×GSD; gap closed -105.1 % (best other: tsdf 83.59, ceiling 99.80, "
        "SAC 66.55)",
        "### Average over blocks (error scale 1; 1 block: city)", "## Error scale 2.5",
        "### city (procedural city, preset small, seed 7; block `city-small-seed7-e2.5`, error scale 2.5)", "| sac | 1 | 66.55 |", "## Ablations (",
        "| sac, fusion.unary: paper | failed |", "## Failed rows",
        "- ablation / city-small-seed7-e1 / sac, fusion.unary: paper: config key rejected second line",
        "Redundancy = result points inside the eval mask / (mask area / GSD²)", "Gap closed ="}) {
    EXPECT_NE(md.find(expected), std::string::npos) << "missing: " << expected << "\n" << md;
  }
}

TEST(QualityBenchFormatTest, JsonHasRowsSummariesAveragesAndSkippedBlocks) {
  const nlohmann::json j = BenchToJson(Document());
  EXPECT_EQ(j["command"], "sacfuse bench --out X");
  ASSERT_EQ(j["rows"].size(), 7u);
  EXPECT_EQ(j["rows"][0]["name"], "sac");
  EXPECT_DOUBLE_EQ(j["rows"][0]["f1_2gsd_pct"].get<double>(), 66.554);
  EXPECT_EQ(j["rows"][0]["points"], 10165096u);
  EXPECT_EQ(j["rows"][0]["folder"], "rows/city-small-seed7-e1/sac");
  EXPECT_FALSE(j["rows"][0].contains("key"));
  EXPECT_TRUE(j["rows"][2]["reused"].get<bool>());
  EXPECT_EQ(j["rows"][6]["status"], "failed");
  EXPECT_TRUE(j["rows"][6]["f1_2gsd_pct"].is_null());
  EXPECT_EQ(j["failed_rows"], 1);
  ASSERT_EQ(j["summaries"].size(), 3u);  // city at 1, city at 2.5, ablations
  EXPECT_EQ(j["summaries"][0]["sac_rank_2gsd"], 2);
  EXPECT_NEAR(j["summaries"][0]["gap_closed"].get<double>(), (66.554 - 83.59) / (99.8 - 83.59), 1e-12);
  ASSERT_EQ(j["averages"].size(), 2u);
  EXPECT_EQ(j["averages"][0]["rows"][0]["blocks"], 1);
  bool skipped = false;
  for (const auto& b : j["blocks"]) skipped |= b["scene"] == "zurich" && b["status"] == "skipped";
  EXPECT_TRUE(skipped) << j["blocks"].dump();
}

}  // namespace
}  // namespace sacfuse::bench
