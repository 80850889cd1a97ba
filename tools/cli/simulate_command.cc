#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/sim/sim_options.h"
#include "tools/sim/simulate.h"

namespace sacfuse::cli {
namespace {

struct SimulateArgs {
  std::string preset = "tiny";
  std::string out_dir;
  uint64_t seed = 1;
  std::string from_las;
  bool no_errors = false;
  bool no_pose_errors = false;  // pose_position_sigma_m = pose_rotation_sigma_deg = 0, other errors as they are
  double error_scale = 1.0;
  bool no_obliques = false;
  bool write_truth = false;
  double truth_ortho_cell_m = 0.0;
  std::optional<bool> consistency_graphs;  // unset = the preset's default
  double area_m = 0.0;
  bool no_normal_maps = false;
  double pixel_scale = 1.0;
  std::string depth = "synthetic";
  int sgbm_min_agree = 0;  // 0 = the default of SgbmDepthOptions
};

// A ready-to-run config next to the block: `sacfuse run DIR/sacfuse.yaml` fuses and scores it. Only the keys the
// block decides are written; every other key takes the defaults of the sacfuse that runs it (a full dump would
// freeze this binary's defaults into the block and hide later changes from reruns and `sacfuse bench`).
void WriteBlockConfig(const std::string& out_dir, const SimOptions& sim) {
  std::ostringstream gsd;
  gsd.precision(15);
  gsd << sim.gsd_m;
  WriteFileAtomically((std::filesystem::path(out_dir) / "sacfuse.yaml").string(),
                      "# Written by `sacfuse simulate`; paths are relative to this file. Keys not given take their\n"
                      "# defaults (`sacfuse run --print-defaults`).\n"
                      "input: {path: \".\"}\n"
                      "output: {dir: \"out\"}\n"
                      "evaluation: {reference: \"reference.las\", mask: \"eval_mask.png\", gsd_m: " +
                          gsd.str() + "}\n");
}

int Simulate(const SimulateArgs& args) {
  SetupLogging("info");
  return RunGuarded([&] {
    SimOptions options = SimPreset(args.preset);
    options.seed = args.seed;
    if (!args.from_las.empty()) {
      options.scene = "las";
      options.from_las = args.from_las;
    }
    if (args.area_m > 0) options.area_width_m = options.area_height_m = args.area_m;
    options.errors.enabled = !args.no_errors;
    options.errors.scale = args.error_scale;
    if (args.no_pose_errors) options.errors.pose_position_sigma_m = options.errors.pose_rotation_sigma_deg = 0.0;
    options.obliques = !args.no_obliques;
    options.write_truth = args.write_truth;
    options.truth_ortho_cell_m = args.truth_ortho_cell_m;
    if (args.consistency_graphs) options.write_consistency_graphs = *args.consistency_graphs;
    options.write_normal_maps = !args.no_normal_maps;
    if (args.pixel_scale <= 0.0 || !std::isfinite(args.pixel_scale)) {
      throw ConfigError("--pixel-scale = " + std::to_string(args.pixel_scale) + ": must be > 0");
    }
    if (args.pixel_scale != 1.0) ScaleSimPixels(args.pixel_scale, &options);
    options.depth = args.depth;
    if (args.sgbm_min_agree > 0) options.sgbm.min_agree = args.sgbm_min_agree;
    ValidateSimOptions(options);
    SetupLogging("info", (std::filesystem::path(args.out_dir) / "simulate.log").string());
    spdlog::info("simulating preset '{}' (seed {}) into {}", options.preset, options.seed, args.out_dir);
    ProgressPrinter progress;
    const SimSummary s = SimulateBlock(options, args.out_dir, std::ref(progress));
    WriteBlockConfig(args.out_dir, options);
    std::cout << "simulated block: " << s.workspace_dir << "\n"
              << "  views: " << s.num_views << " (" << s.num_nadir << " nadir, " << s.num_oblique << " oblique)\n"
              << "  depth pixels: " << s.depth_pixels << ", reference points: " << s.reference_points
              << ", sparse points: " << s.sparse_points << "\n"
              << "  consistency graphs: " << s.consistency_graphs << "\n"
              << "  reference: " << s.reference_las << "\n  eval mask: " << s.eval_mask_png << "\n"
              << "  metadata: " << s.metadata_json << "\n"
              << "  run it: sacfuse run " << (std::filesystem::path(args.out_dir) / "sacfuse.yaml").string() << "\n"
              << "  (" << s.seconds << " s)\n";
    return kExitOk;
  });
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  std::string presets;
  for (const auto& n : SimPresetNames()) presets += (presets.empty() ? "" : ", ") + n;
  auto* cmd = app.add_subcommand("simulate",
                                 "Make a synthetic aerial block (COLMAP workspace + reference LAS + eval mask) with "
                                 "known ground truth and realistic, seeded depth errors");
  cmd->add_option("--preset", args->preset, "Block size: " + presets)->capture_default_str();
  cmd->add_option("--out", args->out_dir, "Output folder")->required();
  cmd->add_option("--seed", args->seed, "Random seed (scene and errors)")->capture_default_str();
  cmd->add_option("--from-las", args->from_las, "Use an airborne LiDAR LAS file as the scene surface");
  cmd->add_option("--area", args->area_m, "Square scene side, metres (overrides the preset; crops --from-las)");
  cmd->add_flag("--no-errors", args->no_errors, "Perfect depth maps and true poses (the ceiling)");
  cmd->add_flag("--no-pose-errors", args->no_pose_errors,
                "True poses (pose_position_sigma_m = pose_rotation_sigma_deg = 0); every other error as it is");
  cmd->add_option("--error-scale", args->error_scale, "Multiply every error magnitude (2-3 = harsher)")
      ->capture_default_str();
  cmd->add_flag("--no-obliques", args->no_obliques, "Nadir camera only");
  cmd->add_flag("--write-truth", args->write_truth, "Also write truth/: error-free depth maps with true poses");
  cmd->add_option("--truth-ortho-cell", args->truth_ortho_cell_m,
                  "Also write truth_ortho.tif: the true scene seen from straight above with the images' shading, on "
                  "cells of this size in metres (the reference of `sacfuse eval --ortho`; 0 = none)")
      ->check(CLI::NonNegativeNumber);
  auto* graphs_on = cmd->add_flag_callback(
      "--consistency-graphs", [args] { args->consistency_graphs = true; },
      "Write stereo/consistency_graphs/ (COLMAP dense-matching consistency; default: on for tiny and small)");
  auto* graphs_off = cmd->add_flag_callback(
      "--no-consistency-graphs", [args] { args->consistency_graphs = false; },
      "Do not write stereo/consistency_graphs/ (default: off for medium and dortmund)");
  graphs_on->excludes(graphs_off);
  cmd->add_flag("--no-normal-maps", args->no_normal_maps,
                "Do not write stereo/normal_maps/ (3x the depth maps on disk; sacfuse does not read them, COLMAP's "
                "stereo_fusion does)");
  cmd->add_option("--pixel-scale", args->pixel_scale,
                  "Scale the image size by this factor at the same flight plan and optics (pixels x s^2, GSD / s): "
                  "the same block at another resolution, e.g. for scaling benchmarks")
      ->capture_default_str();
  cmd->add_option("--depth", args->depth,
                  "Depth maps: synthetic (true depth + the error models) or sgbm (OpenCV StereoSGBM on rectified "
                  "pairs of the rendered images under the written poses: a real matcher's errors, exact truth)")
      ->check(CLI::IsMember({"synthetic", "sgbm"}))
      ->capture_default_str();
  cmd->add_option("--sgbm-min-agree", args->sgbm_min_agree,
                  "With --depth sgbm: stereo pairs that must agree to keep a pixel (default 2; 1 keeps single-pair "
                  "depths, the matcher's raw output)")
      ->check(CLI::Range(1, 16));
  cmd->callback([args, exit_code] { *exit_code = Simulate(*args); });
}

}  // namespace sacfuse::cli
