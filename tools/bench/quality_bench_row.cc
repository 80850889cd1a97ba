#include "tools/bench/quality_bench_row.h"

#include <chrono>
#include <deque>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"
#include "tools/bench/child_process.h"
#include "tools/bench/quality_bench_config.h"
#include "io/json_text.h"

namespace sacfuse::bench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string FormatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
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
  if (fs::exists(dir / "out" / "dsm.tif")) argv.insert(argv.end(), {"--dsm", (dir / "out" / "dsm.tif").string()});
  const ChildResult e = RunRowStep(argv, (dir / "eval.log").string());
  result->eval_s = e.wall_s;
  const RowMetrics wall = result->metrics;
  result->metrics = MetricsFromEvalJson((dir / "eval.json").string(), ev.gsd_m);
  result->metrics.wall_s = wall.wall_s;
  result->metrics.peak_rss_mib = wall.peak_rss_mib;
}

void RunSacfuseRow(const RowSpec& row, const RowContext& c, const BlockEvaluation& ev, RowResult* result) {
  const fs::path dir(c.row_dir);
  const ChildResult r = RunRowStep({c.sacfuse, "run", (dir / "sacfuse.yaml").string()}, (dir / "run.log").string());
  result->metrics.wall_s = r.wall_s;
  result->metrics.peak_rss_mib = r.peak_rss_mib;
  const fs::path report = dir / "out" / "run_report.json";
  if (fs::exists(report)) {
    const json j = ReadJsonFile(report.string());
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
  const ChildResult whole = RunRowStep(argv, (dir / "run.log").string());
  const json j = ReadJsonFile((dir / "out" / "colmap_fusion.json").string());
  fs::copy_file(dir / "out" / "eval.json", dir / "eval.json", fs::copy_options::overwrite_existing);
  result->metrics = MetricsFromEvalJson((dir / "eval.json").string(), ev.gsd_m);
  result->metrics.wall_s = j.value("wall_s", kNoValue);
  result->metrics.peak_rss_mib = j.value("peak_rss_mib", kNoValue);
  result->fusion_wall_s = whole.wall_s;  // the whole colmap-fusion command: shift, COLMAP, convert, scoring
  result->fusion_peak_rss_mib = whole.peak_rss_mib;
  result->tool_version = j.value("colmap_version", std::string());
}

}  // namespace

ChildResult RunRowStep(const std::vector<std::string>& argv, const std::string& log) {
  const ChildResult r = RunChildProcess(argv, log);
  if (r.exit_code != 0) {
    throw Error("`" + JoinWords(argv) + "` failed with exit code " + std::to_string(r.exit_code) + "; last lines of " +
                log + ":\n" + TailOfFile(log, 8));
  }
  return r;
}

json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path, std::string("not valid JSON: ") + e.what());
  }
}

std::optional<json> ReusableRowJson(const std::string& path, const std::string& key, bool force) {
  if (force || !fs::exists(path)) return std::nullopt;
  json old = ReadJsonFile(path);
  const RowResult r = RowResultFromJson(old);
  if (!r.ok() || r.key != key) return std::nullopt;
  return old;
}

void RecordRowJson(const std::string& path, const json& row, RowResult* result) {
  try {
    std::error_code ec;
    fs::create_directories(fs::path(path).parent_path(), ec);
    WriteFileAtomically(path, JsonText(row, 2) + "\n");
  } catch (const std::exception& e) {
    if (result->ok()) {
      result->status = "failed";
      result->error = std::string("cannot record the row: ") + e.what();
    }
  }
}

// What a scored row keeps: the configs, logs, eval.json, run_report.json; the clouds and working copies go.
void DropClouds(const std::string& row_dir) {
  std::error_code ec;
  const fs::path dir(row_dir);
  const fs::path out = dir / "out";
  // The small outputs stay beside row.json: the run's numbers and its DSM (the aerial peers are gridded on its cells).
  for (const char* name : {"run_report.json", "colmap_fusion.json", "dsm.tif"}) {
    if (fs::exists(out / name, ec)) fs::copy_file(out / name, dir / name, fs::copy_options::overwrite_existing, ec);
  }
  fs::remove_all(out, ec);
}

std::string JoinWords(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& a : words) out += (out.empty() ? "" : " ") + a;
  return out;
}

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
    // sacfuse rows write their DSM (the simulated blocks have no `crs`, so it is asked for), scored by eval --dsm.
    if (row.kind != RowKind::kColmap) request.overrides.emplace_back("output.dsm", "on");
    request.keep_evaluation = row.kind == RowKind::kColmap;  // colmap-fusion scores itself
    const std::string config = MakeRowConfig(request);
    std::string command = row.kind == RowKind::kColmap ? "colmap-fusion --colmap " + c.colmap : "run + eval";
    for (const auto& o : row.stereo_fusion) command += " --stereo-fusion " + o;
    result.key = config + "\n# command: " + command + "\n# block: " + BlockStamp(c.block_dir);

    if (const auto old = ReusableRowJson(row_json.string(), result.key, c.force)) {
      RowResult reused = RowResultFromJson(*old);
      reused.reused = true;
      return reused;
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
  if (!c.keep_clouds) DropClouds(dir.string());
  RecordRowJson(row_json.string(), RowResultToJson(result), &result);
  return result;
}

}  // namespace sacfuse::bench
