#include "tools/bench/quality_bench.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"
#include "tools/bench/aerial_bench_rows.h"
#include "tools/bench/child_process.h"
#include "tools/bench/quality_bench_format.h"
#include "tools/bench/quality_bench_machine.h"
#include "tools/bench/quality_bench_row.h"
#include "io/json_text.h"

namespace sacfuse::bench {
namespace {

namespace fs = std::filesystem;

bool BlockComplete(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "metadata.json", ec) && fs::is_regular_file(dir / "sacfuse.yaml", ec);
}

// Simulates the block unless a complete one is there; returns "" or the error text.
std::string EnsureBlock(const BlockSpec& block, const fs::path& dir, const std::string& sacfuse, std::ostream& out) {
  const std::vector<std::string> args = block.SimulateArgs(dir.string());
  const std::string stamp = "sacfuse " + JoinWords(args) + "\n";
  if (BlockComplete(dir)) {
    if (!fs::exists(dir / "bench_block.json")) WriteFileAtomically((dir / "bench_block.json").string(), stamp);
    return "";
  }
  out << "simulating block " << block.id << " ..." << std::flush;
  std::error_code ec;
  fs::remove_all(dir, ec);  // a partial block of a killed bench
  fs::create_directories(dir.parent_path());
  std::vector<std::string> argv = {sacfuse};
  argv.insert(argv.end(), args.begin(), args.end());
  const fs::path log = dir.parent_path() / (block.id + ".simulate.log");
  try {
    const ChildResult r = RunChildProcess(argv, log.string());
    if (r.exit_code != 0 || !BlockComplete(dir)) {
      out << " failed\n";
      return "`sacfuse " + JoinWords(args) + "` failed (exit code " + std::to_string(r.exit_code) + "); last lines of " +
             log.string() + ":\n" + TailOfFile(log.string(), 8);
    }
    WriteFileAtomically((dir / "bench_block.json").string(), stamp);
    char text[32];
    std::snprintf(text, sizeof(text), " %.1f s\n", r.wall_s);
    out << text << std::flush;
  } catch (const std::exception& e) {
    out << " failed\n";
    return e.what();
  }
  return "";
}

std::string ScaleLabel(const RowSpec& row) {
  if (row.section == "ablation") return "ablation";
  std::ostringstream s;
  s << "scale " << row.error_scale;
  return s.str();
}

void PrintProgress(size_t index, size_t total, const RowSpec& row, const RowResult& r, std::ostream& out) {
  out << "[" << index << "/" << total << "] " << row.scene << " " << ScaleLabel(row) << " | " << row.name << ": ";
  if (!r.ok()) {
    std::string first = r.error.substr(0, r.error.find('\n'));
    out << "FAILED: " << first << std::endl;
    return;
  }
  out << "F1 " << FormatFixed(r.metrics.f1_2gsd_pct, 2) << " / " << FormatFixed(r.metrics.f1_5gsd_pct, 2)
      << " %, " << FormatCount(r.metrics.points) << " points, " << FormatFixed(r.metrics.wall_s, 1) << " s"
      << (r.reused ? " (reused)" : "") << std::endl;
}

void RunAerialBlocks(const AerialPlan& plan, const QualityBenchOptions& options, const BenchEnvironment& env,
                     const fs::path& root, BenchDocument* doc, BenchOutcome* outcome, std::ostream& out) {
  AerialContext context;
  context.sacfuse = env.sacfuse;
  context.python = plan.python;
  context.bench_dir = plan.bench_dir;
  context.root = root.string();
  context.colmap = !options.colmap_path.empty();
  context.force = options.force;
  context.keep_clouds = options.keep_clouds;
  for (const AerialBlockSpec& block : plan.blocks) {
    for (AerialRow& row : RunAerialBlock(block, context, out)) {
      ++outcome->rows;
      if (!row.result.ok()) ++outcome->failed_rows;
      if (row.result.reused) ++outcome->reused_rows;
      doc->aerial_rows.push_back(std::move(row));
    }
  }
}

}  // namespace

BenchOutcome RunQualityBench(const QualityBenchOptions& options, const BenchEnvironment& env, std::ostream& out) {
  if (options.out_dir.empty()) throw ConfigError("--out: required (the bench's output folder)");
  const BenchPlan plan = BuildBenchPlan(options);
  const AerialPlan aerial = BuildAerialPlan(options);
  const fs::path root = fs::absolute(options.out_dir);
  fs::create_directories(root / "blocks");
  fs::create_directories(root / "rows");

  BenchDocument doc;
  doc.options = options;
  doc.blocks = plan.blocks;
  doc.skipped = plan.skipped;
  doc.skipped.insert(doc.skipped.end(), aerial.skipped.begin(), aerial.skipped.end());
  for (const SkippedBlock& s : doc.skipped) out << "skipping block " << s.scene << ": " << s.reason << std::endl;
  doc.header.command_line = env.command_line;
  doc.header.date = UtcNow();
  doc.header.machine = DescribeMachine(ReadMachineInfo());
  doc.header.sacfuse_version = env.sacfuse_version;
  doc.header.colmap_note = env.colmap_note;

  std::map<std::string, std::string> block_errors;  // id -> "" (ready) or why it failed
  BenchOutcome outcome;
  size_t index = 0;
  for (const RowSpec& row : plan.rows) {
    ++index;
    const fs::path block_dir = root / "blocks" / row.block_id;
    if (!block_errors.count(row.block_id)) {
      const auto it = std::find_if(plan.blocks.begin(), plan.blocks.end(),
                                   [&](const BlockSpec& b) { return b.id == row.block_id; });
      block_errors[row.block_id] = EnsureBlock(*it, block_dir, env.sacfuse, out);
    }
    BenchRow bench_row{row, {}};
    if (!block_errors[row.block_id].empty()) {
      bench_row.result.error = "block " + row.block_id + " could not be simulated: " + block_errors[row.block_id];
    } else {
      RowContext context;
      context.sacfuse = env.sacfuse;
      context.colmap = options.colmap_path;
      context.block_dir = block_dir.string();
      context.row_dir = (root / "rows" / row.Folder()).string();
      context.force = options.force;
      context.keep_clouds = options.keep_clouds;
      bench_row.result = RunBenchRow(row, context);
    }
    PrintProgress(index, plan.rows.size(), row, bench_row.result, out);
    if (doc.header.colmap_version.empty()) doc.header.colmap_version = bench_row.result.tool_version;
    ++outcome.rows;
    if (!bench_row.result.ok()) ++outcome.failed_rows;
    if (bench_row.result.reused) ++outcome.reused_rows;
    doc.rows.push_back(std::move(bench_row));
  }
  RunAerialBlocks(aerial, options, env, root / "aerial", &doc, &outcome, out);
  Summarise(&doc);
  outcome.markdown_path = (root / "bench.md").string();
  outcome.json_path = (root / "bench.json").string();
  WriteFileAtomically(outcome.markdown_path, FormatBenchMarkdown(doc));
  WriteFileAtomically(outcome.json_path, JsonText(BenchToJson(doc), 2) + "\n");
  return outcome;
}

}  // namespace sacfuse::bench
