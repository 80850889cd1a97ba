#pragma once
// `sacfuse bench`: every fusion method on simulated blocks with known truth, scored alike, as one Markdown and one
// JSON table (a Table-I-like comparison; see quality_bench_plan.h for the blocks and rows). Blocks are simulated
// by child `sacfuse simulate` runs into OUT/blocks/<id> (reused when complete); each row runs and is scored as in
// quality_bench_row.h into OUT/rows/<block id>/<row>; OUT/bench.md and OUT/bench.json are written atomically at
// the end. Progress goes to `out` row by row. A failed row (or block) is recorded and the bench goes on.
#include <ostream>
#include <string>

#include "tools/bench/quality_bench_plan.h"

namespace sacfuse::bench {

struct BenchEnvironment {
  std::string sacfuse;          // the sacfuse binary run as the child processes (/proc/self/exe)
  std::string command_line;     // for the header
  std::string sacfuse_version;
  std::string colmap_note;      // shown when no COLMAP row ran: "off (--colmap off)", "not found on PATH"
};

struct BenchOutcome {
  int rows = 0;
  int failed_rows = 0;
  int reused_rows = 0;
  std::string markdown_path, json_path;
};

// Throws ConfigError for bad options (before anything is written) and Error when OUT cannot be written.
BenchOutcome RunQualityBench(const QualityBenchOptions& options, const BenchEnvironment& env, std::ostream& out);

}  // namespace sacfuse::bench
