#include "tools/bench/quality_bench_row.h"

#include <chrono>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"
#include "tools/bench/child_process.h"
#include "tools/bench/quality_bench_config.h"

namespace sacfuse::bench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Join(const std::vector<std::string>& argv) {
  std::string out;
  for (const auto& a : argv) out += (out.empty() ? "" : " ") + a;
  return out;
}

std::string FormatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "cannot open");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path.string(), std::string("not valid JSON: ") + e.what());
  }
}

// Runs a child; throws Error with the log's tail when it fails.
ChildResult RunStep(const std::vector<std::string>& argv, const fs::path& log) {
  const ChildResult r = RunChildProcess(argv, log.string());
  if (r.exit_code != 0) {
    throw Error("`" + Join(argv) + "` failed with exit code " + std::to_string(r.exit_code) + "; last lines of " +
                log.string() + ":\n" + TailOfFile(log.string(), 8));
  }
  return r;
}

// The block's simulate stamp (its arguments), so a re-simulated block invalidates the rows on it.
std::string BlockStamp(const fs::path& block_dir) {
  std::ifstream in(block_dir / "bench_block.json");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void ScoreSacfuseRow(const RowSpec& row, const RowContext& c, const BlockEvaluation& ev, RowResult* result) {
  const fs::path dir(c.row_dir);
  const fs::path las = dir / "out" / "fused.las";
  std::vector<std::string> argv = {c.sacfuse, "eval", las.string(), "--reference", ev.reference};
  if (!ev.mask.empty()) argv.insert(argv.end(), {"--mask", ev.mask});
  std::string taus;
  for (const double t : ev.tau_gsd) taus += (taus.empty() ? "" : ",") + FormatNumber(t);
  argv.insert(argv.end(), {"--gsd", FormatNumber(ev.gsd_m), "--tau-gsd", taus, "--json", (dir / "eval.json").string()});
  if (ev.align) argv.push_back("--align");
  const ChildResult e = RunStep(argv, dir / "eval.log");
  result->eval_s = e.wall_s;
  const RowMetrics wall = result->metrics;
  result->metrics = MetricsFromEvalJson((dir / "eval.json").string(), ev.gsd_m);
  result->metrics.wall_s = wall.wall_s;
  result->metrics.peak_rss_mib = wall.peak_rss_mib;
}

void RunSacfuseRow(const RowSpec& row, const RowContext& c, const BlockEvaluation& ev, RowResult* result) {
  const fs::path dir(c.row_dir);
  const ChildResult r = RunStep({c.sacfuse, "run", (dir / "sacfuse.yaml").string()}, dir / "run.log");
  result->metrics.wall_s = r.wall_s;
  result->metrics.peak_rss_mib = r.peak_rss_mib;
  const fs::path report = dir / "out" / "run_report.json";
  if (fs::exists(report)) {
    const json j = ReadJson(report);
    if (j.contains("wall_seconds") && j["wall_seconds"].is_number()) result->fusion_wall_s = j["wall_seconds"];
    if (j.contains("peak_rss_mib") && j["peak_rss_mib"].is_number()) result->fusion_peak_rss_mib = j["peak_rss_mib"];
  }
  ScoreSacfuseRow(row, c, ev, result);
}

void RunColmapRow(const RowSpec& row, const RowContext& c, const BlockEvaluation& ev, RowResult* result) {
  const fs::path dir(c.row_dir);
  std::vector<std::string> argv = {c.sacfuse, "colmap-fusion", (dir / "sacfuse.yaml").string(), "--out",
                                   (dir / "out").string(), "--colmap", c.colmap};
  for (const std::string& option : row.stereo_fusion) argv.insert(argv.end(), {"--stereo-fusion", option});
  const ChildResult whole = RunStep(argv, dir / "run.log");
  const json j = ReadJson(dir / "out" / "colmap_fusion.json");
  fs::copy_file(dir / "out" / "eval.json", dir / "eval.json", fs::copy_options::overwrite_existing);
  result->metrics = MetricsFromEvalJson((dir / "eval.json").string(), ev.gsd_m);
  result->metrics.wall_s = j.value("wall_s", kNoValue);
  result->metrics.peak_rss_mib = j.value("peak_rss_mib", kNoValue);
  result->fusion_wall_s = whole.wall_s;  // the whole colmap-fusion command: shift, COLMAP, convert, scoring
  result->fusion_peak_rss_mib = whole.peak_rss_mib;
  result->tool_version = j.value("colmap_version", std::string());
}

// What a scored row keeps: the configs, logs, eval.json, run_report.json; the clouds and working copies go.
void DropClouds(const fs::path& dir) {
  std::error_code ec;
  const fs::path out = dir / "out";
  if (fs::exists(out / "run_report.json", ec)) fs::copy_file(out / "run_report.json", dir / "run_report.json",
                                                              fs::copy_options::overwrite_existing, ec);
  if (fs::exists(out / "colmap_fusion.json", ec)) fs::copy_file(out / "colmap_fusion.json",
                                                                 dir / "colmap_fusion.json",
                                                                 fs::copy_options::overwrite_existing, ec);
  fs::remove_all(out, ec);
}

}  // namespace

std::string TailOfFile(const std::string& path, int lines) {
  std::ifstream in(path);
  std::deque<std::string> tail;
  std::string line;
  while (std::getline(in, line)) {
    tail.push_back(line);
    if (static_cast<int>(tail.size()) > lines) tail.pop_front();
  }
  std::string out;
  for (const auto& l : tail) out += l + "\n";
  return out;
}

RowResult RunBenchRow(const RowSpec& row, const RowContext& c) {
  const fs::path dir(c.row_dir);
  const fs::path block_config = fs::path(c.block_dir) / "sacfuse.yaml";
  const fs::path row_json = dir / "row.json";
  RowResult result;
  try {
    RowConfigRequest request;
    request.block_config = block_config.string();
    request.output_dir = (dir / "out").string();
    request.overrides = row.overrides;
    request.keep_evaluation = row.kind == RowKind::kColmap;  // colmap-fusion scores itself
    const std::string config = MakeRowConfig(request);
    std::string command = row.kind == RowKind::kColmap ? "colmap-fusion --colmap " + c.colmap : "run + eval";
    for (const auto& o : row.stereo_fusion) command += " --stereo-fusion " + o;
    result.key = config + "\n# command: " + command + "\n# block: " + BlockStamp(c.block_dir);

    if (!c.force && fs::exists(row_json)) {
      RowResult old = RowResultFromJson(ReadJson(row_json));
      if (old.ok() && old.key == result.key) {
        old.reused = true;
        return old;
      }
    }
    std::error_code ec;
    fs::remove_all(dir, ec);  // cold start: no cached superpixels, no stale outputs
    fs::create_directories(dir);
    WriteFileAtomically((dir / "sacfuse.yaml").string(), config);
    const BlockEvaluation ev = ReadBlockEvaluation(block_config.string());
    if (ev.reference.empty()) throw InputError(block_config.string(), "no evaluation.reference to score against");
    if (row.kind == RowKind::kColmap) {
      RunColmapRow(row, c, ev, &result);
    } else {
      RunSacfuseRow(row, c, ev, &result);
    }
    result.status = "ok";
  } catch (const std::exception& e) {
    result.status = "failed";
    result.error = e.what();
  }
  if (!c.keep_clouds) DropClouds(dir);
  try {
    std::error_code ec;
    fs::create_directories(dir, ec);
    WriteFileAtomically(row_json.string(), RowResultToJson(result).dump(2) + "\n");
  } catch (const std::exception& e) {
    if (result.ok()) {
      result.status = "failed";
      result.error = std::string("cannot record the row: ") + e.what();
    }
  }
  return result;
}

}  // namespace sacfuse::bench
