#pragma once
// `sacfuse bench`, part 5: the table maths on finished rows. A group is the rows of one block at one error scale
// (or the ablation rows). Per group: SAC's rank among the methods (ceiling excluded) at 2 and 5 x GSD and the
// share of the gap to the ceiling SAC closes over the best other method; per error scale: every column averaged
// over the blocks where the row ran.
#include <string>
#include <vector>

#include "tools/bench/quality_bench_plan.h"
#include "tools/bench/quality_bench_result.h"

namespace sacfuse::bench {

struct BenchRow {
  RowSpec spec;
  RowResult result;
};

// (F1_sac - F1_best_other) / (F1_ceiling - F1_best_other): 1 = SAC reaches the ceiling, 0 = no better than the
// best other method, < 0 = worse than it. NaN when an input is NaN or the ceiling is not above the best other.
double GapClosed(double f1_sac, double f1_best_other, double f1_ceiling);

// 1 + the number of values strictly greater than `value` (ties share a rank); NaN values are not counted.
int RankOf(double value, const std::vector<double>& values);

struct GroupSummary {
  std::string section;             // "main" | "ablation"
  std::string scene;
  double error_scale = 1.0;
  int ranked = 0;                  // rows ranked: successful, not the ceiling
  int sac_rank_2gsd = 0;           // 0 = no successful SAC row
  int sac_rank_5gsd = 0;
  double sac_f1_2gsd = kNoValue;
  std::string best_other;          // best successful non-SAC, non-ceiling row at 2 x GSD
  double best_other_f1_2gsd = kNoValue;
  double ceiling_f1_2gsd = kNoValue;
  double gap_closed = kNoValue;    // GapClosed at 2 x GSD
};

// Groups in order of first appearance (rows of a group need not be adjacent).
std::vector<GroupSummary> SummariseGroups(const std::vector<BenchRow>& rows);

struct AverageRow {
  std::string name;
  int blocks = 0;                  // blocks where this row succeeded (the mean's count)
  RowMetrics mean;                 // each column's mean over those blocks (points rounded)
};

struct ScaleAverage {
  double error_scale = 1.0;
  std::vector<std::string> scenes; // blocks with at least one successful row at this scale
  std::vector<AverageRow> rows;    // in first-appearance order
  double gap_closed = kNoValue;    // mean over blocks where it is defined
  double sac_rank_2gsd = kNoValue; // mean over blocks with a SAC row
  double sac_rank_5gsd = kNoValue;
};

// One per error scale of the main section, in first-appearance order.
std::vector<ScaleAverage> AverageOverBlocks(const std::vector<BenchRow>& rows,
                                            const std::vector<GroupSummary>& summaries);

}  // namespace sacfuse::bench
