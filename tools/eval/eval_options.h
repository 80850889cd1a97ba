#pragma once
// Options of `sacfuse eval`: accuracy / completeness / F1 of a result cloud against a reference cloud, after
// ETH3D's protocol adapted to airborne references (see eval.h for the exact definitions).
#include <string>
#include <vector>

namespace sacfuse {

struct EvalOptions {
  double gsd_m = 0.10;                    // ground sampling distance, metres; sets the defaults below
  std::vector<double> tau_gsd = {2.0, 5.0};  // distance thresholds as multiples of gsd_m
  std::vector<double> tau_m;              // explicit thresholds in metres (override tau_gsd when non-empty)
  double voxel_m = 0.0;                   // cell of the density normalisation, metres (0 = gsd_m)
  std::string mask_path;                  // GeoMask PNG (with JSON sidecar) limiting the evaluation; "" = none
  bool align = false;                     // robust ICP of the result onto the reference before scoring
  int align_max_iterations = 30;
  double align_max_points = 200000;       // subsample for ICP
  double top_cell_m = 0.0;                // XY cell of the reference top-surface model, metres (0 = 4 x gsd)
  std::string json_path;                  // write the report as JSON here ("" = none)
};

}  // namespace sacfuse
