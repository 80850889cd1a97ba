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
  // Result clouds with more points are scored on every k-th point (k = ceil(points / this)), so scoring stays
  // inside a memory budget (~72 bytes per scored point). 0 = every point.
  double max_result_points = 0;

  // --- Added by the eval module (defaults keep the behaviour documented in eval.h) ---
  // Completeness counts a reference point only when cameras can see it: z >= occluder - max(tau, this), metres.
  double visible_margin_m = 0.5;
  // ICP: "point_to_plane" (reference normals from 10 neighbours; best for roofs and terrain) or "point_to_point".
  std::string align_mode = "point_to_plane";
  double align_trim_fraction = 0.8;       // ICP keeps this fraction of correspondences (the closest), in (0, 1]
  double align_max_distance_m = 2.0;      // ICP drops correspondences farther apart than this, metres
  unsigned align_seed = 1;                // seed of the ICP subsample (runs are deterministic)
};

// The thresholds in metres, sorted ascending and de-duplicated: tau_m when given, else tau_gsd x gsd_m.
std::vector<double> EvalThresholds(const EvalOptions& options);
// Effective voxel size and top-surface cell, metres.
double EvalVoxelSize(const EvalOptions& options);
double EvalTopCellSize(const EvalOptions& options);

// Throws ConfigError listing every broken rule as "eval.<key> = <value>: <rule>".
void ValidateEvalOptions(const EvalOptions& options);

}  // namespace sacfuse
