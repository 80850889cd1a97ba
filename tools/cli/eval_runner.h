#pragma once
// Scoring a fused cloud against a reference and printing the table; shared by `run` and `eval`.
#include <ostream>
#include <string>
#include <vector>

namespace sacfuse::cli {

struct EvalRequest {
  std::string result_las;
  std::string reference_las;
  std::string mask_png;                   // "" = none
  double gsd_m = 0.10;
  std::vector<double> tau_gsd = {2.0, 5.0};
  std::vector<double> tau_m;              // explicit thresholds (override tau_gsd)
  bool align = false;
  std::string json_path;                  // "" = no JSON
};

// Prints the table and a one-line F1 summary to `out`; writes JSON when asked. Throws on bad input.
void RunEvaluation(const EvalRequest& request, std::ostream& out);

}  // namespace sacfuse::cli
