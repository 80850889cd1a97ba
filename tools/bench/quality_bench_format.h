#pragma once
// `sacfuse bench`, part 6: the finished bench as Markdown (bench.md) and JSON (bench.json). Numbers: F1,
// accuracy, completeness in % with 2 decimals; mean absolute distance in m with 3; points with thousands
// separators; redundancy with 2; wall time in s with 1; peak RSS in MiB with 0; "–" for a missing value and
// "failed" for a failed row (its error is listed below the tables).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/bench/aerial_bench_table.h"
#include "tools/bench/quality_bench_plan.h"
#include "tools/bench/quality_bench_table.h"

namespace sacfuse::bench {

struct BenchHeader {
  std::string command_line;
  std::string date;             // UtcNow()
  std::string machine;          // DescribeMachine()
  std::string sacfuse_version;
  std::string colmap_version;   // "" = COLMAP rows not run
  std::string colmap_note;      // why not (off, not found), or the binary
};

struct BenchDocument {
  BenchHeader header;
  QualityBenchOptions options;
  std::vector<BlockSpec> blocks;
  std::vector<SkippedBlock> skipped;
  std::vector<BenchRow> rows;                // plan order
  std::vector<GroupSummary> summaries;       // SummariseGroups(rows)
  std::vector<ScaleAverage> averages;        // AverageOverBlocks(rows, summaries)
  std::vector<AerialRow> aerial_rows;        // aerial-bench blocks (aerial_bench_rows.h), block by block
  std::vector<AerialSummary> aerial_summaries;  // SummariseAerial(aerial_rows)
};

// Fills summaries, averages and aerial_summaries from the rows.
void Summarise(BenchDocument* document);

std::string FormatBenchMarkdown(const BenchDocument& document);
nlohmann::json BenchToJson(const BenchDocument& document);

// Cell formatting (exposed for tests): "–" for NaN.
std::string FormatFixed(double value, int decimals);
std::string FormatCount(uint64_t value);  // 1234567 -> "1,234,567"

}  // namespace sacfuse::bench
