#include "tools/bench/quality_bench_format.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "tools/bench/aerial_bench_format.h"
#include "tools/bench/quality_bench_result.h"

namespace sacfuse::bench {
namespace {

using nlohmann::json;

const char* const kColumnsHeader =
    "| method | F1 2×GSD % | F1 5×GSD % | accuracy 2× % | completeness 2× % | mean abs dist m | points | "
    "redundancy | DSM NMAD m | DSM compl. % | wall s | peak RSS MiB |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";

std::string Cells(const RowMetrics& m) {
  return FormatFixed(m.f1_2gsd_pct, 2) + " | " + FormatFixed(m.f1_5gsd_pct, 2) + " | " +
         FormatFixed(m.accuracy_2gsd_pct, 2) + " | " + FormatFixed(m.completeness_2gsd_pct, 2) + " | " +
         FormatFixed(m.mean_abs_distance_m, 3) + " | " + FormatCount(m.points) + " | " + FormatFixed(m.redundancy, 2) +
         " | " + FormatFixed(m.dsm_nmad_m, 3) + " | " + FormatFixed(m.dsm_completeness_pct, 2) + " | " +
         FormatFixed(m.wall_s, 1) + " | " + FormatFixed(m.peak_rss_mib, 0);
}

std::string RowLine(const BenchRow& r) {
  std::string name = r.spec.is_sac ? "**" + r.spec.name + "**" : r.spec.name;
  if (r.result.reused) name += " ↺";
  if (!r.result.ok()) return "| " + name + " | failed | | | | | | | | | | |\n";
  return "| " + name + " | " + Cells(r.result.metrics) + " |\n";
}

std::string Number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string SummaryLine(const GroupSummary& g) {
  std::string out = "SAC: ";
  if (g.sac_rank_2gsd == 0) return out + "no successful SAC row.\n";
  out += "rank " + std::to_string(g.sac_rank_2gsd) + " of " + std::to_string(g.ranked) + " at 2×GSD, " +
         std::to_string(g.sac_rank_5gsd) + " of " + std::to_string(g.ranked) + " at 5×GSD; gap closed " +
         (std::isfinite(g.gap_closed) ? FormatFixed(100.0 * g.gap_closed, 1) + " %" : std::string("–"));
  if (!g.best_other.empty()) {
    out += " (best other: " + g.best_other + " " + FormatFixed(g.best_other_f1_2gsd, 2) + ", ceiling " +
           FormatFixed(g.ceiling_f1_2gsd, 2) + ", SAC " + FormatFixed(g.sac_f1_2gsd, 2) + ")";
  }
  return out + ".\n";
}

const BlockSpec* FindBlock(const BenchDocument& d, const std::string& id) {
  for (const BlockSpec& b : d.blocks) {
    if (b.id == id) return &b;
  }
  return nullptr;
}

// The block of a main-section group (scene at an error scale), for its heading.
std::string DescribeBlock(const BenchDocument& d, const GroupSummary& g) {
  for (const BenchRow& r : d.rows) {
    if (r.spec.section != "main" || r.spec.scene != g.scene || r.spec.error_scale != g.error_scale ||
        r.spec.is_ceiling) {
      continue;
    }
    const BlockSpec* b = FindBlock(d, r.spec.block_id);
    if (b == nullptr) continue;
    std::string text =
        b->from_las.empty() ? "procedural city" : "LiDAR " + std::filesystem::path(b->from_las).filename().string();
    text += ", preset " + b->preset + ", seed " + std::to_string(b->seed);
    if (b->area_m > 0) text += ", area " + Number(b->area_m) + " m";
    return text + "; block `" + b->id + "`";
  }
  return "";
}

void AppendNotes(const BenchDocument& d, std::ostringstream& md) {
  md << "\n## Notes\n\n"
     << "- Scores: `sacfuse eval` with each block's evaluation settings (reference LiDAR/truth, eval mask, GSD); "
        "F1, accuracy and completeness are the density-normalised (primary) values in %, at τ = 2× and 5× the "
        "block's GSD. Mean abs dist: mean nearest-reference distance of the observed result points at 2×GSD, m.\n"
     << "- Redundancy = result points inside the eval mask / (mask area / GSD²): points per GSD×GSD cell of the "
        "evaluated area (1.0 = one point per cell; the union of all depth maps is the most redundant).\n"
     << "- DSM: each sacfuse row writes its DSM (`output.dsm: on`, automatic cell) and `sacfuse eval --dsm` scores "
        "it against the reference's top surface on the same cells over the eval mask: NMAD of the height error, m, "
        "and completeness (share of the cells with a value), %. COLMAP rows have no DSM.\n"
     << "- Wall s and peak RSS MiB: the fusion command alone as a child process (wait4): `sacfuse run` (reading "
        "the workspace, fusing, writing fused.las; no scoring) for sacfuse rows, COLMAP's `stereo_fusion` process "
        "for COLMAP rows (the workspace shift, PLY→LAS conversion and scoring are not included). Each sacfuse row "
        "starts cold (no cached superpixels). Rows run one after the other, each with all cores.\n"
     << "- Ceiling: `union` on the same block simulated with `--no-errors` (same scene, cameras, perfect depth, "
        "true poses). Gap closed = (F1_SAC − F1_best other) / (F1_ceiling − F1_best other) at 2×GSD; the best "
        "other is the best successful row that is neither SAC nor the ceiling (COLMAP rows included). Rank: "
        "SAC's place among the successful rows of the block (ceiling excluded; ties share a rank).\n"
     << "- COLMAP rows: `sacfuse colmap-fusion` at COLMAP's defaults, and with `--StereoFusion.max_normal_error "
        "180`: COLMAP's normal test (10°) rejects most of the simulated depth, whose normal maps are 3×3 plane fits "
        "on noisy depth, so the default row says more about the simulator than about COLMAP.\n"
     << "- ↺: result reused from an earlier bench run with the same config and block (resume; `--force` re-runs).\n"
     << "- Average over blocks: per error scale, each column's mean over the blocks where the row succeeded "
        "(count in the blocks column).\n";
  (void)d;
}

}  // namespace

std::string FormatFixed(double value, int decimals) {
  if (!std::isfinite(value)) return "–";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

std::string FormatCount(uint64_t value) {
  std::string digits = std::to_string(value);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

void Summarise(BenchDocument* d) {
  d->summaries = SummariseGroups(d->rows);
  d->averages = AverageOverBlocks(d->rows, d->summaries);
  d->aerial_summaries = SummariseAerial(d->aerial_rows);
}

std::string FormatBenchMarkdown(const BenchDocument& d) {
  std::ostringstream md;
  const BenchHeader& h = d.header;
  md << "# sacfuse bench: fusion quality on simulated blocks\n\n"
     << "- command: `" << h.command_line << "`\n"
     << "- date: " << h.date << "\n"
     << "- machine: " << h.machine << "\n"
     << "- sacfuse: " << h.sacfuse_version << "\n"
     << "- COLMAP: " << (h.colmap_version.empty() ? h.colmap_note : h.colmap_version) << "\n"
     << "- seed " << d.options.seed << ", preset " << d.options.preset << ", error scales";
  for (const double s : d.options.error_scales) md << " " << Number(s);
  if (d.options.depth != "synthetic") md << ", depth maps " << d.options.depth << " (simulate --depth)";
  md << "\n";
  for (const SkippedBlock& s : d.skipped) md << "- skipped block " << s.scene << ": " << s.reason << "\n";

  for (const ScaleAverage& a : d.averages) {
    md << "\n## Error scale " << Number(a.error_scale) << "\n";
    for (const GroupSummary& g : d.summaries) {
      if (g.section != "main" || g.error_scale != a.error_scale) continue;
      md << "\n### " << g.scene << " (" << DescribeBlock(d, g) << ", error scale "
         << Number(g.error_scale) << ")\n\n"
         << kColumnsHeader;
      for (const BenchRow& r : d.rows) {
        if (r.spec.section == "main" && r.spec.scene == g.scene && r.spec.error_scale == g.error_scale) md << RowLine(r);
      }
      md << "\n" << SummaryLine(g);
    }
    md << "\n### Average over blocks (error scale " << Number(a.error_scale) << "; " << a.scenes.size()
       << " block" << (a.scenes.size() == 1 ? "" : "s") << ":";
    for (const auto& s : a.scenes) md << " " << s;
    md << ")\n\n"
       << "| method | blocks | F1 2×GSD % | F1 5×GSD % | accuracy 2× % | completeness 2× % | mean abs dist m | "
          "points | redundancy | DSM NMAD m | DSM compl. % | wall s | peak RSS MiB |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const AverageRow& r : a.rows) {
      md << "| " << r.name << " | " << r.blocks << " | " << Cells(r.mean)
         << " |\n";
    }
    md << "\nSAC: mean rank " << FormatFixed(a.sac_rank_2gsd, 2) << " at 2×GSD, " << FormatFixed(a.sac_rank_5gsd, 2)
       << " at 5×GSD; mean gap closed "
       << (std::isfinite(a.gap_closed) ? FormatFixed(100.0 * a.gap_closed, 1) + " %" : std::string("–")) << ".\n";
  }

  for (const GroupSummary& g : d.summaries) {
    if (g.section != "ablation") continue;
    md << "\n## Ablations (";
    for (const BenchRow& r : d.rows) {
      if (r.spec.section == "ablation" && r.spec.is_sac) {
        const BlockSpec* b = FindBlock(d, r.spec.block_id);
        if (b != nullptr) md << "procedural city, preset " << b->preset << ", seed " << b->seed << ", error scale 1; block `" << b->id << "`";
        break;
      }
    }
    md << ")\n\nOne option changed from the default per row (or the block: without pose errors, no errors).\n\n"
       << kColumnsHeader;
    for (const BenchRow& r : d.rows) {
      if (r.spec.section == "ablation") md << RowLine(r);
    }
  }

  md << FormatAerialMarkdown(d.aerial_rows, d.aerial_summaries);

  std::vector<std::pair<std::string, std::string>> failed;  // where, error
  for (const BenchRow& r : d.rows) {
    if (!r.result.ok()) failed.emplace_back(r.spec.section + " / " + r.spec.block_id + " / " + r.spec.name, r.result.error);
  }
  for (const AerialRow& r : d.aerial_rows) {
    if (!r.result.ok()) failed.emplace_back("aerial-bench / " + r.block + " / " + r.method, r.result.error);
  }
  if (!failed.empty()) md << "\n## Failed rows\n\n";
  for (auto& [where, error] : failed) {
    for (char& c : error) {
      if (c == '\n') c = ' ';
    }
    md << "- " << where << ": " << error << "\n";
  }
  AppendNotes(d, md);
  return md.str();
}

json BenchToJson(const BenchDocument& d) {
  json j;
  const BenchHeader& h = d.header;
  j["command"] = h.command_line;
  j["date"] = h.date;
  j["machine"] = h.machine;
  j["sacfuse_version"] = h.sacfuse_version;
  j["colmap_version"] = h.colmap_version;
  j["colmap_note"] = h.colmap_note;
  j["options"] = {{"seed", d.options.seed},
                  {"preset", d.options.preset},
                  {"error_scales", d.options.error_scales},
                  {"depth", d.options.depth},
                  {"methods", d.options.methods},
                  {"ablations", d.options.ablations},
                  {"ablation_preset", d.options.ablation_preset},
                  {"lidar_dir", d.options.lidar_dir},
                  {"colmap", d.options.colmap_path},
                  {"aerial_bench_dir", d.options.aerial_bench_dir},
                  {"aerial_blocks", d.options.aerial_blocks}};
  json blocks = json::array();
  for (const BlockSpec& b : d.blocks) {
    blocks.push_back({{"id", b.id}, {"scene", b.scene}, {"status", "used"}, {"preset", b.preset},
                      {"from_las", b.from_las}, {"area_m", b.area_m}, {"seed", b.seed},
                      {"error_scale", b.error_scale}, {"no_errors", b.no_errors},
                      {"no_pose_errors", b.no_pose_errors}, {"consistency_graphs", b.consistency_graphs},
                      {"depth", b.depth}});
  }
  for (const SkippedBlock& s : d.skipped) blocks.push_back({{"scene", s.scene}, {"status", "skipped"}, {"reason", s.reason}});
  j["blocks"] = blocks;
  json rows = json::array();
  int failed = 0;
  for (const BenchRow& r : d.rows) {
    json row = RowResultToJson(r.result);
    row.erase("key");
    row["section"] = r.spec.section;
    row["scene"] = r.spec.scene;
    row["error_scale"] = r.spec.error_scale;
    row["name"] = r.spec.name;
    row["block_id"] = r.spec.block_id;
    row["kind"] = r.spec.kind == RowKind::kColmap ? "colmap" : "sacfuse";
    row["is_sac"] = r.spec.is_sac;
    row["is_ceiling"] = r.spec.is_ceiling;
    row["folder"] = "rows/" + r.spec.Folder();
    json overrides = json::object();
    for (const auto& [k, v] : r.spec.overrides) overrides[k] = v;
    row["overrides"] = overrides;
    row["stereo_fusion"] = r.spec.stereo_fusion;
    if (!r.result.ok()) ++failed;
    rows.push_back(row);
  }
  j["rows"] = rows;
  for (const AerialRow& r : d.aerial_rows) failed += r.result.ok() ? 0 : 1;
  j["failed_rows"] = failed;
  j["aerial_rows"] = AerialRowsToJson(d.aerial_rows);
  j["aerial_summaries"] = AerialSummariesToJson(d.aerial_summaries);
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json summaries = json::array();
  for (const GroupSummary& g : d.summaries) {
    summaries.push_back({{"section", g.section}, {"scene", g.scene}, {"error_scale", g.error_scale},
                         {"ranked", g.ranked}, {"sac_rank_2gsd", g.sac_rank_2gsd},
                         {"sac_rank_5gsd", g.sac_rank_5gsd}, {"sac_f1_2gsd_pct", num(g.sac_f1_2gsd)},
                         {"best_other", g.best_other}, {"best_other_f1_2gsd_pct", num(g.best_other_f1_2gsd)},
                         {"ceiling_f1_2gsd_pct", num(g.ceiling_f1_2gsd)}, {"gap_closed", num(g.gap_closed)}});
  }
  j["summaries"] = summaries;
  json averages = json::array();
  for (const ScaleAverage& a : d.averages) {
    json arows = json::array();
    for (const AverageRow& r : a.rows) {
      RowResult tmp;
      tmp.status = "ok";
      tmp.metrics = r.mean;
      json m = RowResultToJson(tmp);
      json row = {{"name", r.name}, {"blocks", r.blocks}};
      for (const char* k : {"f1_2gsd_pct", "f1_5gsd_pct", "accuracy_2gsd_pct", "completeness_2gsd_pct",
                            "mean_abs_distance_m", "points", "redundancy", "dsm_nmad_m", "dsm_completeness_pct",
                            "wall_s", "peak_rss_mib"}) {
        row[k] = m[k];
      }
      arows.push_back(row);
    }
    averages.push_back({{"error_scale", a.error_scale}, {"scenes", a.scenes}, {"rows", arows},
                        {"gap_closed", num(a.gap_closed)}, {"sac_rank_2gsd", num(a.sac_rank_2gsd)},
                        {"sac_rank_5gsd", num(a.sac_rank_5gsd)}});
  }
  j["averages"] = averages;
  return j;
}

}  // namespace sacfuse::bench
