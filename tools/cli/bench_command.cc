// `sacfuse bench --out DIR`: the quality benchmark table (issue 6): every fusion method (and COLMAP's
// stereo_fusion when installed) on simulated blocks with known truth, scored alike, with the no-errors ceiling and
// the SAC ablations. The work is in tools/bench/quality_bench.h.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "config/version.h"
#include "tools/bench/aerial_bench_plan.h"
#include "tools/bench/child_process.h"
#include "tools/bench/quality_bench.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"

namespace sacfuse::cli {
namespace {

struct BenchArgs {
  bench::QualityBenchOptions options;
  std::string colmap = "auto";
  std::string lidar_dir;  // "" = DefaultLidarDir()
  std::string aerial_bench = "auto";  // auto | off | DIR
  bool quick = false;
  bool no_ablations = false;
  // Which options the command line set (they win over --quick).
  CLI::Option* blocks = nullptr;
  CLI::Option* scales = nullptr;
  CLI::Option* preset = nullptr;
  CLI::Option* methods = nullptr;
  CLI::Option* ablation_preset = nullptr;
  CLI::Option* colmap_option = nullptr;
  CLI::Option* aerial_option = nullptr;
  CLI::Option* aerial_blocks = nullptr;
};

// --aerial-bench: "off" clears the blocks; "auto" is DefaultAerialBenchDir() ("" when missing: skipped).
void ResolveAerialBench(const std::string& aerial_bench, bench::QualityBenchOptions* o) {
  if (aerial_bench == "off") {
    o->aerial_blocks.clear();
    return;
  }
  o->aerial_bench_dir = aerial_bench == "auto" ? bench::DefaultAerialBenchDir() : aerial_bench;
}

std::string ResolveColmap(const std::string& colmap, std::string* note) {
  if (colmap == "off") {
    *note = "not run (--colmap off)";
    return "";
  }
  const std::string name = colmap == "auto" ? "colmap" : colmap;
  const std::string path = FindExecutable(name);
  if (path.empty()) {
    if (colmap != "auto") throw ConfigError("--colmap = '" + colmap + "': no such executable");
    *note = "not found on PATH (apt-get install colmap; or --colmap PATH)";
  }
  return path;
}

// This process's command line from /proc/self/cmdline, words joined by spaces (program name as "sacfuse").
std::string OwnCommandLine() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string line;
  size_t start = 0;
  bool first = true;
  while (start < text.size()) {
    size_t end = text.find('\0', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    line += first ? "sacfuse" : " " + (word.find(' ') == std::string::npos ? word : "'" + word + "'");
    first = false;
    start = end + 1;
  }
  return line.empty() ? "sacfuse bench" : line;
}

int BenchCommand(BenchArgs& args) {
  SetupLogging("warn");
  return RunGuarded([&] {
    bench::QualityBenchOptions o = args.options;
    if (args.quick) {
      const bench::QualityBenchOptions given = o;
      bench::ApplyQuickPreset(&o);
      if (args.blocks->count() > 0) o.blocks = given.blocks;
      if (args.scales->count() > 0) o.error_scales = given.error_scales;
      if (args.preset->count() > 0) o.preset = given.preset;
      if (args.methods->count() > 0) o.methods = given.methods;
      if (args.ablation_preset->count() > 0) o.ablation_preset = given.ablation_preset;
      if (args.colmap_option->count() == 0) args.colmap = "off";
      if (args.aerial_option->count() > 0 || args.aerial_blocks->count() > 0) o.aerial_blocks = given.aerial_blocks;
    }
    if (args.no_ablations) o.ablations = false;
    o.lidar_dir = args.lidar_dir.empty() ? bench::DefaultLidarDir() : args.lidar_dir;
    ResolveAerialBench(args.aerial_bench, &o);
    bench::BenchEnvironment env;
    env.command_line = OwnCommandLine();
    env.sacfuse_version = FullVersionString();
    o.colmap_path = ResolveColmap(args.colmap, &env.colmap_note);
    std::error_code ec;
    env.sacfuse = std::filesystem::read_symlink("/proc/self/exe", ec).string();
    if (env.sacfuse.empty()) throw Error("cannot find this program's own path (/proc/self/exe)");
    const bench::BenchOutcome outcome = bench::RunQualityBench(o, env, std::cout);
    std::cout << outcome.rows << " rows (" << outcome.reused_rows << " reused, " << outcome.failed_rows
              << " failed); tables: " << outcome.markdown_path << ", " << outcome.json_path << "\n";
    return outcome.failed_rows > 0 ? kExitFailure : kExitOk;
  });
}

}  // namespace

void AddBenchCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<BenchArgs>();
  bench::QualityBenchOptions& o = args->options;
  auto* cmd = app.add_subcommand(
      "bench",
      "Quality benchmark: simulate blocks (procedural city, LiDAR cities) with known truth, fuse each with every "
      "fusion.method (and COLMAP's stereo_fusion when installed), score alike, write DIR/bench.md and "
      "DIR/bench.json. Resumable: finished rows are reused");
  cmd->add_option("--out", o.out_dir, "Output folder (blocks/, rows/, bench.md, bench.json)")->required();
  std::string names;
  for (const auto& n : bench::BlockNames()) names += (names.empty() ? "" : ",") + n;
  args->blocks = cmd->add_option("--blocks", o.blocks, "Blocks, comma-separated: " + names + " (default: city, "
                                 "zurich, montpellier; autzen and semis have references too sparse for 2 x GSD; a "
                                 "LiDAR block whose file is missing is skipped)")
                     ->delimiter(',');
  args->scales = cmd->add_option("--error-scales", o.error_scales,
                                 "Error scales (simulate --error-scale), one block each, comma-separated")
                     ->delimiter(',')
                     ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Simulation seed of every block")->capture_default_str();
  cmd->add_option("--depth", o.depth,
                  "Depth maps of the main blocks: synthetic (error models) or sgbm (simulate --depth sgbm: matched "
                  "by StereoSGBM from the rendered images); the ceiling and the ablations stay synthetic")
      ->check(CLI::IsMember({"synthetic", "sgbm"}))
      ->capture_default_str();
  args->preset = cmd->add_option("--preset", o.preset, "Simulate preset of the main blocks")->capture_default_str();
  args->methods = cmd->add_option("--methods", o.methods, "fusion.method rows, comma-separated")
                      ->delimiter(',')
                      ->capture_default_str();
  args->colmap_option =
      cmd->add_option("--colmap", args->colmap, "COLMAP rows: auto (when colmap is on PATH) | off | PATH")
          ->capture_default_str();
  cmd->add_flag("--no-ablations", args->no_ablations, "Leave out the ablation rows");
  args->ablation_preset = cmd->add_option("--ablation-preset", o.ablation_preset,
                                          "Simulate preset of the ablation block (procedural city)")
                              ->capture_default_str();
  cmd->add_option("--lidar-dir", args->lidar_dir,
                  "Folder of the LiDAR files (default: $SACFUSE_SHARED/research-data/lidar, else "
                  "../shared/research-data/lidar next to the source tree)");
  args->aerial_option =
      cmd->add_option("--aerial-bench", args->aerial_bench,
                      "aerial-bench blocks beside ours: auto ($SACFUSE_SHARED/aerial-bench, else "
                      "../shared/aerial-bench next to the source tree; skipped with a message when missing) | off | "
                      "DIR")
          ->capture_default_str();
  std::string aerial_names;
  for (const auto& n : bench::AerialBlockNames()) aerial_names += (aerial_names.empty() ? "" : ",") + n;
  args->aerial_blocks = cmd->add_option("--aerial-blocks", o.aerial_blocks,
                                        "aerial-bench blocks, comma-separated (default: " + aerial_names +
                                            "; made once in OUT/aerial/<name> by its make_block.py)")
                            ->delimiter(',');
  cmd->add_flag("--force", o.force, "Re-run rows whose result exists");
  cmd->add_flag("--keep-clouds", o.keep_clouds, "Keep every row's fused LAS (default: deleted once scored)");
  cmd->add_flag("--quick", args->quick,
                "Tests/CI preset: tiny preset, city only, scale 1, methods sac,union,tsdf, 2 ablation rows, no "
                "COLMAP, no aerial-bench (options given explicitly still apply)");
  cmd->callback([args, exit_code] { *exit_code = BenchCommand(*args); });
}

}  // namespace sacfuse::cli
