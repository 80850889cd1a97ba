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
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/bench/child_process.h"
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

// The steps every bench row is made of (also the aerial-bench rows, aerial_bench_rows.h):
// Runs a child (child_process.h) with its output in `log`; throws Error naming the command, its exit code and the
// log's tail when it fails.
ChildResult RunRowStep(const std::vector<std::string>& argv, const std::string& log);
// Parses a JSON file; throws InputError naming it.
nlohmann::json ReadJsonFile(const std::string& path);
// The row.json at `path` when it succeeded with this key and `force` is off (resume), else nothing.
std::optional<nlohmann::json> ReusableRowJson(const std::string& path, const std::string& key, bool force);
// Writes `row` (RowResultToJson(*result) plus any extra fields) atomically to `path`; a row that cannot be recorded
// becomes failed.
void RecordRowJson(const std::string& path, const nlohmann::json& row, RowResult* result);
// Removes ROW/out (the clouds) after keeping its run_report.json, colmap_fusion.json and dsm.tif in ROW.
void DropClouds(const std::string& row_dir);

// argv joined by spaces (commands in errors, logs and resume keys).
std::string JoinWords(const std::vector<std::string>& words);

// The last `lines` lines of a text file ("" when it cannot be read): error context from a child's log.
std::string TailOfFile(const std::string& path, int lines);

}  // namespace sacfuse::bench
