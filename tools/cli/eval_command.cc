#include <iostream>

#include <CLI/CLI.hpp>

#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "eval/eval_runner.h"

namespace sacfuse::cli {

void AddEvalCommand(CLI::App& app, int* exit_code) {
  auto request = std::make_shared<EvalRequest>();
  auto* cmd = app.add_subcommand(
      "eval",
      "Score a fused cloud against a reference cloud: accuracy, completeness and F1 at several thresholds "
      "(averaged over voxel cells so density does not bias them), mean absolute distance, points per m2, "
      "source-view histogram");
  cmd->add_option("RESULT", request->result_las, "The fused LAS file")->required();
  cmd->add_option("--reference", request->reference_las, "Reference LAS (e.g. airborne LiDAR)")->required();
  cmd->add_option("--mask", request->mask_png, "Evaluation mask PNG with its JSON sidecar");
  cmd->add_option("--gsd", request->gsd_m, "Ground sampling distance, metres")->capture_default_str();
  cmd->add_option("--tau-gsd", request->tau_gsd, "Thresholds in GSD units")->delimiter(',')->capture_default_str();
  cmd->add_option("--tau", request->tau_m, "Thresholds in metres (override --tau-gsd)")->delimiter(',');
  cmd->add_flag("--align", request->align, "Robust ICP of the result onto the reference before scoring");
  cmd->add_option("--json", request->json_path, "Also write the report as JSON here");
  cmd->add_option("--dsm", request->dsm,
                  "Also score this DSM (GeoTIFF or VRT) against the reference's top surface on its cells: "
                  "completeness, median, NMAD, RMSE, by class");
  cmd->add_option("--ortho", request->ortho,
                  "Also score this RGBA orthophoto (GeoTIFF or VRT) against --ortho-reference on their common cells, "
                  "beside the ortho of RESULT's point colours: coverage, PSNR, SSIM, edge displacement");
  cmd->add_option("--ortho-reference", request->ortho_reference,
                  "Reference orthophoto on the same cell lattice (e.g. truth_ortho.tif of `sacfuse simulate "
                  "--truth-ortho-cell`)");
  cmd->callback([request, exit_code] {
    SetupLogging("info");
    *exit_code = RunGuarded([&] {
      RunEvaluation(*request, std::cout);
      return kExitOk;
    });
  });
}

}  // namespace sacfuse::cli
