// FormatEvalTable: the human-readable report of eval.h.
#include <cinttypes>
#include <cstdio>
#include <string>

#include <Eigen/Geometry>

#include "eval/eval.h"

namespace sacfuse {
namespace {

template <typename... Args>
std::string Format(const char* fmt, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof(buf), fmt, args...);
  return buf;
}

}  // namespace

std::string FormatEvalTable(const EvalReport& r) {
  std::string out;
  out += Format("result:    %" PRIu64 " points (%" PRIu64 " evaluated, %" PRIu64 " unobserved, %" PRIu64
                " outside the mask)\n",
                r.result_points, r.result_points_evaluated, r.result_points_unobserved,
                r.result_points_outside_mask);
  out += Format("reference: %" PRIu64 " points (%" PRIu64 " visible inside the mask)\n", r.reference_points,
                r.reference_points_evaluated);
  out += "   tau [m]  accuracy  complete.        F1 |  raw acc. raw comp.    raw F1\n";
  for (const ThresholdScore& s : r.scores) {
    out += Format("%10.3f %8.2f%% %8.2f%% %8.2f%% | %8.2f%% %8.2f%% %8.2f%%\n", s.tau_m, 100 * s.accuracy,
                  100 * s.completeness, 100 * s.f1, 100 * s.raw_accuracy, 100 * s.raw_completeness, 100 * s.raw_f1);
  }
  out += Format("distance to reference: mean %.4f m, median %.4f m (observed result points)\n",
                r.mean_abs_distance_m, r.median_abs_distance_m);
  out += Format("area %.1f m2, %.2f result points / m2\n", r.area_m2, r.points_per_m2);
  if (r.aligned) {
    const Eigen::Matrix3d rot = r.alignment.topLeftCorner<3, 3>();
    const double angle_deg = Eigen::AngleAxisd(rot).angle() * 180.0 / 3.14159265358979323846;
    out += Format("alignment (robust ICP): rotation %.4f deg, translation (%.4f, %.4f, %.4f) m at the origin\n",
                  angle_deg, r.alignment(0, 3), r.alignment(1, 3), r.alignment(2, 3));
  }
  if (!r.source_id_histogram.empty()) {
    out += Format("point source IDs: %zu distinct;", r.source_id_histogram.size());
    size_t shown = 0;
    for (const auto& [id, count] : r.source_id_histogram) {
      if (shown++ == 12) {
        out += " ...";
        break;
      }
      out += Format(" %u:%" PRIu64, static_cast<unsigned>(id), count);
    }
    out += "\n";
  }
  return out;
}

}  // namespace sacfuse
