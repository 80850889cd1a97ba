#include "eval/eval_options.h"

#include <algorithm>
#include <cmath>

#include "core/option_check.h"

namespace sacfuse {

std::vector<double> EvalThresholds(const EvalOptions& options) {
  std::vector<double> taus = options.tau_m;
  if (taus.empty()) {
    for (double k : options.tau_gsd) taus.push_back(k * options.gsd_m);
  }
  std::sort(taus.begin(), taus.end());
  taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
  return taus;
}

double EvalVoxelSize(const EvalOptions& options) {
  return options.voxel_m > 0.0 ? options.voxel_m : options.gsd_m;
}

double EvalTopCellSize(const EvalOptions& options) {
  return options.top_cell_m > 0.0 ? options.top_cell_m : 4.0 * options.gsd_m;
}

void ValidateEvalOptions(const EvalOptions& o) {
  OptionChecker c;
  // Like OptionChecker::Greater / AtLeast, but infinity and NaN fail too.
  auto positive = [&](const std::string& key, double v) {
    c.Require(std::isfinite(v) && v > 0.0, key, OptionChecker::ToString(v), "must be > 0");
  };
  auto non_negative = [&](const std::string& key, double v, const std::string& note) {
    c.Require(std::isfinite(v) && v >= 0.0, key, OptionChecker::ToString(v), "must be >= 0" + note);
  };
  positive("eval.gsd_m", o.gsd_m);
  c.Require(!o.tau_m.empty() || !o.tau_gsd.empty(), "eval.tau_gsd", "[]",
            "give at least one threshold (tau_m or tau_gsd)");
  for (size_t i = 0; i < o.tau_m.size(); ++i) positive("eval.tau_m[" + std::to_string(i) + "]", o.tau_m[i]);
  for (size_t i = 0; i < o.tau_gsd.size(); ++i) positive("eval.tau_gsd[" + std::to_string(i) + "]", o.tau_gsd[i]);
  non_negative("eval.voxel_m", o.voxel_m, " (0 = gsd_m)");
  non_negative("eval.top_cell_m", o.top_cell_m, " (0 = 4 x gsd_m)");
  non_negative("eval.visible_margin_m", o.visible_margin_m, "");
  c.AtLeast("eval.align_max_iterations", o.align_max_iterations, 1);
  c.Require(std::isfinite(o.max_result_points) && o.max_result_points >= 0, "eval.max_result_points",
            OptionChecker::ToString(o.max_result_points), "must be >= 0 (0 = every point)");
  c.Require(std::isfinite(o.align_max_points) && o.align_max_points >= 100, "eval.align_max_points",
            OptionChecker::ToString(o.align_max_points), "must be >= 100");
  c.OneOf("eval.align_mode", o.align_mode, {"point_to_plane", "point_to_point"});
  c.Require(o.align_trim_fraction > 0.0 && o.align_trim_fraction <= 1.0, "eval.align_trim_fraction",
            OptionChecker::ToString(o.align_trim_fraction), "must be in (0, 1]");
  positive("eval.align_max_distance_m", o.align_max_distance_m);
  c.ThrowIfFailed("sacfuse eval");
}

}  // namespace sacfuse
