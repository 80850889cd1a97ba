#pragma once
// `sacfuse bench`, part 4: running one row. The fusion runs as a child process of the sacfuse binary
// (child_process.h), so its wall time and peak RSS are its own:
//  * sacfuse rows: `sacfuse run ROW/sacfuse.yaml` (the block config with the row's keys and no evaluation section,
//    output in ROW/out, started cold: ROW/out is removed first), then `sacfuse eval` of ROW/out/fused.las with the
//    block's evaluation settings into ROW/eval.json;
//  * COLMAP rows: `sacfuse colmap-fusion ROW/sacfuse.yaml --out ROW/out --colmap PATH [--stereo-fusion N=V]`; its
//    time and memory are COLMAP's stereo_fusion process (colmap_fusion.json), its scores out/eval.json.
// The result is written atomically to ROW/row.json with a key (config text, command, block); a later bench with
// the same key reuses it (resume) unless forced. The row's clouds are deleted once scored unless kept.
#include <string>
#include <vector>

#include "tools/bench/quality_bench_plan.h"
#include "tools/bench/quality_bench_result.h"

namespace sacfuse::bench {

struct RowContext {
  std::string sacfuse;          // the sacfuse binary
  std::string colmap;           // COLMAP binary for COLMAP rows
  std::string block_dir;        // the simulated block the row runs on
  std::string row_dir;          // OUT/rows/<RowSpec::Folder()>
  bool force = false;
  bool keep_clouds = false;
};

// Never throws for a failing row: the error text is in the result (status "failed").
RowResult RunBenchRow(const RowSpec& row, const RowContext& context);

// The last `lines` lines of a text file ("" when it cannot be read): error context from a child's log.
std::string TailOfFile(const std::string& path, int lines);

}  // namespace sacfuse::bench
