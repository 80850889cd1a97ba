#include "tools/bench/aerial_bench_rows.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/gdal_raster.h"
#include "io/las_copy.h"
#include "tools/bench/quality_bench_format.h"
#include "tools/bench/quality_bench_row.h"

namespace sacfuse::bench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// COLMAP's grid in peers.py's colmap_best (its best setting on these blocks).
const std::vector<std::string> kColmapGrid = {"--grid", "max_normal_error=180", "--grid", "min_num_pixels=2,5",
                                              "--grid", "max_reproj_error=1,2"};

std::string FormatNumber(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::string Script(const AerialContext& c, const char* name) { return (fs::path(c.bench_dir) / name).string(); }

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Makes the block unless its meta.json is there; "" or why it failed.
std::string EnsureBlock(const AerialBlockSpec& b, const AerialContext& c, const fs::path& dir, std::ostream& out) {
  std::error_code ec;
  if (fs::is_regular_file(dir / "meta.json", ec)) return "";
  out << "making aerial-bench block " << b.name << " ..." << std::flush;
  std::vector<std::string> argv = {c.python, Script(c, "make_block.py")};
  try {
    for (const std::string& arg : b.make_args) {
      if (std::find(b.laz_inputs.begin(), b.laz_inputs.end(), arg) == b.laz_inputs.end()) {
        argv.push_back(arg);
        continue;
      }
      const fs::path decoded = fs::path(c.root) / "lidar" / (fs::path(arg).stem().string() + ".las");
      if (!fs::is_regular_file(decoded, ec)) {
        fs::create_directories(decoded.parent_path());
        CopyLasFile(arg, decoded.string(), /*compressed=*/false);
      }
      argv.push_back(decoded.string());
    }
    argv.insert(argv.end(), {"--out", dir.string(), "--force"});
    const ChildResult r = RunRowStep(argv, (fs::path(c.root) / (b.name + ".make.log")).string());
    if (!fs::is_regular_file(dir / "meta.json", ec)) throw Error("make_block.py wrote no " + (dir / "meta.json").string());
    out << " " << FormatFixed(r.wall_s, 1) << " s\n";
  } catch (const std::exception& e) {
    out << " failed\n";
    return e.what();
  }
  return "";
}

// The blocks have no `crs` key: the DSM is asked for (output.dsm: on) at its automatic cell.
std::string SacfuseConfig(const fs::path& block_dir, const fs::path& out_dir) {
  return "input: {format: colmap, path: " + json(block_dir.string()).dump() + "}\noutput: {dir: " +
         json(out_dir.string()).dump() + ", format: las, dsm: \"on\"}\n";
}

// score_dsm.py of a DSM raster or a cloud (extra: e.g. --offset X Y Z); the log is `log`.
AerialDsmScore ScoreDsm(const AerialContext& c, const fs::path& block_dir, const std::string& result,
                        const std::vector<std::string>& extra, const fs::path& log) {
  std::vector<std::string> argv = {c.python, Script(c, "score_dsm.py"), result, "--block", block_dir.string(),
                                   "--json-only"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  RunRowStep(argv, log.string());
  return ParseScoreDsmOutput(ReadText(log), log.string());
}

void RunAndScore(const AerialContext& c, const fs::path& block_dir, const fs::path& dir, const std::string& config,
                 AerialRow* row) {
  std::error_code ec;
  fs::remove_all(dir, ec);  // cold start
  fs::create_directories(dir);
  WriteFileAtomically((dir / "sacfuse.yaml").string(), config);
  const ChildResult r = RunRowStep({c.sacfuse, "run", (dir / "sacfuse.yaml").string()}, (dir / "run.log").string());
  row->result.metrics.wall_s = r.wall_s;
  row->result.metrics.peak_rss_mib = r.peak_rss_mib;
  const fs::path log = dir / "score.log";
  const ChildResult s = RunRowStep({c.python, Script(c, "score.py"), (dir / "out" / "fused.las").string(), "--block",
                                    block_dir.string(), "--json-only"},
                                   log.string());
  row->result.eval_s = s.wall_s;
  row->score = ParseScoreOutput(ReadText(log), log.string());
  row->dsm = ScoreDsm(c, block_dir, (dir / "out" / "dsm.tif").string(), {}, dir / "score_dsm.log");
  row->dsm_p90 = ScoreDsm(c, block_dir, (dir / "out" / "fused.las").string(), {}, dir / "score_dsm_p90.log");
  row->result.status = "ok";
}

AerialRow SacfuseRow(const AerialBlockSpec& b, const AerialContext& c, const fs::path& block_dir) {
  AerialRow row{b.name, "sacfuse", {}, {}, {}, {}};
  const fs::path dir = fs::path(c.root) / "rows" / b.name / "sacfuse";
  const fs::path row_json = dir / "row.json";
  const std::string config = SacfuseConfig(block_dir, dir / "out");
  row.result.key = config + "# command: run + score.py --json-only + score_dsm.py\n# block: make_block.py " +
                   JoinWords(b.make_args);
  try {
    if (const auto old = ReusableRowJson(row_json.string(), row.result.key, c.force)) {
      row.result = RowResultFromJson(*old);
      row.result.reused = true;
      row.score = AerialScoreFromJson(old->value("aerial", json::object()), row_json.string());
      row.dsm = AerialDsmScoreFromJson(old->value("aerial_dsm", json::object()), row_json.string());
      row.dsm_p90 = AerialDsmScoreFromJson(old->value("aerial_dsm_p90", json::object()), row_json.string());
      return row;
    }
    RunAndScore(c, block_dir, dir, config, &row);
  } catch (const std::exception& e) {
    row.result.status = "failed";
    row.result.error = e.what();
  }
  row.result.metrics.f1_2gsd_pct = 100.0 * row.score.f1_2gsd;
  row.result.metrics.f1_5gsd_pct = 100.0 * row.score.f1_5gsd;
  if (!c.keep_clouds) DropClouds(dir.string());
  json j = RowResultToJson(row.result);
  j["aerial"] = AerialScoreToJson(row.score);
  j["aerial_dsm"] = AerialDsmScoreToJson(row.dsm);
  j["aerial_dsm_p90"] = AerialDsmScoreToJson(row.dsm_p90);
  RecordRowJson(row_json.string(), j, &row.result);
  return row;
}

std::map<std::string, AerialPeer> ReadPeers(const fs::path& block_dir) {
  const fs::path path = block_dir / "peers.json";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return {};
  return ParsePeersJson(ReadJsonFile(path.string()), path.string());
}

// Runs peers.py for the methods peers.json lacks (or has failed); returns those it ran, or throws Error.
std::vector<std::string> EnsurePeers(const AerialBlockSpec& b, const AerialContext& c, const fs::path& block_dir,
                                     std::ostream& out) {
  const std::map<std::string, AerialPeer> have = ReadPeers(block_dir);
  std::vector<std::string> missing;
  for (const std::string& m : AerialPeerMethods(c.colmap)) {
    const auto it = have.find(m);
    if (c.force || it == have.end() || !it->second.ok) missing.push_back(m);
  }
  if (missing.empty()) return missing;
  std::string methods;
  for (const std::string& m : missing) methods += (methods.empty() ? "" : ",") + m;
  out << "aerial-bench peers on " << b.name << ": " << methods << " ..." << std::flush;
  std::vector<std::string> argv = {c.python, Script(c, "peers.py"), "--block", block_dir.string(), "--methods", methods};
  if (std::find(missing.begin(), missing.end(), "colmap_best") != missing.end()) {
    argv.insert(argv.end(), kColmapGrid.begin(), kColmapGrid.end());
  }
  try {
    const ChildResult r = RunRowStep(argv, (fs::path(c.root) / (b.name + ".peers.log")).string());
    out << " " << FormatFixed(r.wall_s, 1) << " s\n";
  } catch (const std::exception&) {
    out << " failed\n";
    throw;
  }
  return missing;
}

// The DSM scores of a peer's cloud (BLOCK/peers/<method>.ply, in the block's local frame: shifted by meta.json's
// origin): `sacfuse dsm` on the cells of sacfuse's own DSM (its cell and extent), scored by score_dsm.py, and the
// cloud gridded by score_dsm.py's own rule. Nothing (the row keeps no DSM scores) without sacfuse's DSM or the cloud.
void ScorePeerDsm(const AerialContext& c, const fs::path& block_dir, const std::string& block, AerialRow* row) {
  const fs::path cloud = block_dir / "peers" / (row->method + ".ply");
  const fs::path sac_row = fs::path(c.root) / "rows" / block / "sacfuse";
  std::error_code ec;
  // The run's DSM: beside row.json once the clouds are dropped (DropClouds), else in out/.
  const fs::path sac_dsm = fs::is_regular_file(sac_row / "dsm.tif", ec) ? sac_row / "dsm.tif" : sac_row / "out" / "dsm.tif";
  if (!fs::is_regular_file(cloud, ec) || !fs::is_regular_file(sac_dsm, ec)) return;
  const json origin = ReadJsonFile((block_dir / "meta.json").string()).at("origin");
  std::vector<std::string> offset;
  for (const json& v : origin) offset.push_back(FormatNumber(v.get<double>()));
  const CellWindow w = RasterFile(sac_dsm.string()).window();
  const fs::path dir = fs::path(c.root) / "rows" / block / row->method;
  fs::create_directories(dir);
  const auto centre = [](double edge, double half) { return FormatNumber(edge + half); };
  const double h = 0.5 * w.cell_m;
  RunRowStep({c.sacfuse, "dsm", cloud.string(), "--offset", offset[0] + "," + offset[1] + "," + offset[2], "--cell",
              FormatNumber(w.cell_m), "--extent",
              centre(w.west(), h) + "," + centre(w.south(), h) + "," + centre(w.east(), -h) + "," + centre(w.north(), -h),
              "--out", (dir / "dsm.tif").string()},
             (dir / "dsm.log").string());
  row->dsm = ScoreDsm(c, block_dir, (dir / "dsm.tif").string(), {}, dir / "score_dsm.log");
  row->dsm_p90 = ScoreDsm(c, block_dir, cloud.string(), {"--offset", offset[0], offset[1], offset[2]},
                          dir / "score_dsm_p90.log");
}

std::vector<AerialRow> PeerRows(const AerialBlockSpec& b, const AerialContext& c, const fs::path& block_dir,
                                std::ostream& out) {
  std::vector<std::string> ran;
  std::string error;
  std::map<std::string, AerialPeer> peers;
  try {
    ran = EnsurePeers(b, c, block_dir, out);
    peers = ReadPeers(block_dir);
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::vector<AerialRow> rows;
  for (const std::string& m : AerialPeerMethods(true)) {
    const auto it = peers.find(m);
    // COLMAP rows off (--colmap off, or colmap not installed): COLMAP's row is still shown when the block's
    // peers.json has it, so that "best peer" and half-way are judged against every peer measured.
    if (m == "colmap_best" && !c.colmap && (it == peers.end() || !it->second.ok)) continue;
    AerialRow row{b.name, m, {}, {}, {}, {}};
    if (it == peers.end()) {
      row.result.error = error.empty() ? "peers.py wrote no " + m + " row in " + (block_dir / "peers.json").string()
                                       : error;
    } else if (!it->second.ok) {
      row.result.error = it->second.error + "; see " + (fs::path(c.root) / (b.name + ".peers.log")).string();
    } else {
      row.result.status = "ok";
      row.result.reused = std::find(ran.begin(), ran.end(), m) == ran.end();
      row.score = it->second.score;
      row.result.metrics.wall_s = it->second.wall_s;
      row.result.metrics.peak_rss_mib = it->second.peak_rss_mib;
      row.result.metrics.f1_2gsd_pct = 100.0 * row.score.f1_2gsd;
      row.result.metrics.f1_5gsd_pct = 100.0 * row.score.f1_5gsd;
      if (m == "colmap_best" || m == "tsdf") {
        try {
          ScorePeerDsm(c, block_dir, b.name, &row);
        } catch (const std::exception& e) {
          out << "[aerial] " << b.name << " | " << AerialMethodLabel(m) << ": DSM not scored: " << e.what() << "\n";
        }
      }
    }
    rows.push_back(row);
  }
  return rows;
}

void PrintRow(const AerialRow& r, std::ostream& out) {
  out << "[aerial] " << r.block << " | " << AerialMethodLabel(r.method) << ": ";
  if (!r.result.ok()) {
    out << "FAILED: " << r.result.error.substr(0, r.result.error.find('\n')) << std::endl;
    return;
  }
  out << "F1 " << FormatFixed(r.score.f1_2gsd, 4) << " / " << FormatFixed(r.score.f1_5gsd, 4) << ", "
      << (r.dsm.ok() ? "DSM NMAD " + FormatFixed(r.dsm.nmad_m, 3) + " m, completeness " +
                           FormatFixed(100.0 * r.dsm.completeness, 2) + " %, "
                     : std::string())
      << FormatFixed(r.score.density_per_m2, 1) << " points/m2, " << FormatFixed(r.result.metrics.wall_s, 1) << " s"
      << (r.result.reused ? " (reused)" : "") << std::endl;
}

}  // namespace

std::vector<std::string> AerialPeerMethods(bool colmap) {
  std::vector<std::string> methods = {"tsdf", "union", "oracle"};
  if (colmap) methods.insert(methods.begin(), "colmap_best");
  return methods;
}

std::vector<AerialRow> RunAerialBlock(const AerialBlockSpec& b, const AerialContext& c, std::ostream& out) {
  const fs::path block_dir = fs::path(c.root) / b.name;
  fs::create_directories(c.root);
  std::vector<AerialRow> rows;
  const std::string block_error = EnsureBlock(b, c, block_dir, out);
  if (block_error.empty()) {
    rows.push_back(SacfuseRow(b, c, block_dir));
    PrintRow(rows.back(), out);  // before the peers, which may take minutes
    for (AerialRow& r : PeerRows(b, c, block_dir, out)) {
      PrintRow(r, out);
      rows.push_back(std::move(r));
    }
    return rows;
  }
  std::vector<std::string> methods = AerialPeerMethods(c.colmap);
  methods.insert(methods.begin(), "sacfuse");
  for (const std::string& m : methods) {
    AerialRow row{b.name, m, {}, {}, {}, {}};
    row.result.error = "aerial-bench block " + b.name + " could not be made: " + block_error;
    PrintRow(row, out);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace sacfuse::bench
