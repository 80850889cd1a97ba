#pragma once
// `sacfuse bench`, aerial-bench part 4: its table in bench.md and its rows in bench.json. F1 as fractions with 4
// decimals (score.py's protocol v2), points in the mask per m2 with 1, the ratio to TSDF's points with 2, free
// space (above_top) in % with 2, wall s with 1, peak RSS MiB with 0; "–" for a missing value.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/bench/aerial_bench_table.h"

namespace sacfuse::bench {

// The "## aerial-bench" section: one table of every block's rows, then one line per block (SAC's ranks, half-way
// to the oracle). "" when there are no rows.
std::string FormatAerialMarkdown(const std::vector<AerialRow>& rows, const std::vector<AerialSummary>& summaries);

nlohmann::json AerialRowsToJson(const std::vector<AerialRow>& rows);
nlohmann::json AerialSummariesToJson(const std::vector<AerialSummary>& summaries);

}  // namespace sacfuse::bench
