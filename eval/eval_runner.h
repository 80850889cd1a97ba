#pragma once
// Scoring a fused cloud against a reference and printing the table; shared by `run` and `eval`.
#include <ostream>
#include <string>
#include <vector>

#include "config/job_config.h"
#include "eval/eval.h"

namespace sacfuse {

struct EvalRequest {
  std::string result_las;
  std::string reference_las;
  std::string mask_png;                   // "" = none
  double gsd_m = 0.10;
  std::vector<double> tau_gsd = {2.0, 5.0};
  std::vector<double> tau_m;              // explicit thresholds (override tau_gsd)
  bool align = false;
  std::string json_path;                  // "" = no JSON
  double max_result_points = 0;           // score every k-th point beyond this many (0 = all; EvalOptions)
  std::string dsm;                        // a DSM raster to score too (eval/dsm_accuracy.h); "" = none
  // An RGBA orthophoto to score against ortho_reference, beside the ortho of the result's point colours
  // (eval/ortho_accuracy.h); "" = none (both or neither).
  std::string ortho;
  std::string ortho_reference;
};

// The scoring a job config asks for (evaluation.*), of `result_las` (and of the run's DSM when it wrote one), with
// its JSON at `json_path`; clouds too
// large for half of resources.memory_gb (~72 bytes per scored point, measured) are scored on every k-th point.
// Shared by `run` and `colmap-fusion`, so both score alike.
EvalRequest EvalRequestFromConfig(const JobConfig& config, const std::string& result_las,
                                  const std::string& json_path);

// Prints the table and a one-line F1 summary to `out`; writes JSON when asked; returns the report. Throws on bad
// input.
EvalReport RunEvaluation(const EvalRequest& request, std::ostream& out);

}  // namespace sacfuse
