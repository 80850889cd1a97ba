#include "core/view_noise.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include "core/depth_combine.h"
#include "core/median.h"
#include "core/method_views.h"
#include "core/patch_grid.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

constexpr double kMedianChiSquare1 = 0.4549;  // median of chi^2 with one degree of freedom
constexpr double kMeanPull = 1e-3;            // weight of the pull of each k^2 towards the mean

struct PairRow {
  uint32_t v = 0, b = 0;
  double a = 0.0;   // weight of k_v^2
  double m = 0.0;   // observed mix
};

// The rows of one view v: one per view it consults (at each sample's own point) with enough residuals, in view
// order. `prior_k` empty: the secant's slope over one GSD; else over max(1 GSD, options.slope_step_sigmas sigma of
// v's depth under prior_k), as the combine takes it.
std::vector<PairRow> PairRowsOf(const std::vector<SacView>& views, uint32_t v, const ConsultedViews& consulted,
                                const ViewNoiseOptions& options, const std::vector<double>& prior_k) {
  const SacView& view = views[v];
  const DepthMap& depth = *view.depth;
  std::vector<std::vector<double>> ratio(views.size()), share(views.size());  // per other view b
  CheckCombineViewCount(consulted.max_list_size());
  ViewPoint at_depth[kMaxCombineViews];
  auto add_sample = [&](int row, int col) {
    const float d = depth.at(row, col);
    if (!IsValidDepth(d)) return;
    const std::vector<uint32_t>& others = consulted.At(v, PixelPoint(view, row, col, d));
    const double gsd = view.GsdAt(d);
    const double s_v = DepthNoiseScale(view, d);
    const double own_sigma_m = prior_k.empty() ? 0.0 : prior_k[v] * s_v;  // under the first pass's k
    const double step_m = prior_k.empty() ? gsd : SecantStepM(gsd, own_sigma_m, options.slope_step_sigmas);
    const SecantPoints ray = SecantPointsOnRay(view, col + 0.5, row + 0.5, d, step_m);
    ProjectForSecants(views, others, ray.at_depth, at_depth);
    for (size_t i = 0; i < others.size(); ++i) {
      double gate_m = options.gate_gsd * gsd;
      if (!prior_k.empty() && options.gate_sigmas > 0 && at_depth[i].in_front) {
        // sigma of the pair's difference (the neighbour's at the point's depth in it)
        const double pair_sigma_m = PairSigmaM(own_sigma_m, DepthSigmaM(views, prior_k, others[i], at_depth[i].z_m));
        gate_m = std::max(gate_m, options.gate_sigmas * pair_sigma_m);
      }
      RayHit hit;
      if (!IntersectRay(views[others[i]], at_depth[i], ray.at_next, d, step_m, gate_m, options.min_slope, &hit)) {
        continue;
      }
      const double s_b = DepthNoiseScale(views[others[i]], hit.z_b_m) / std::abs(hit.slope);
      const double total = s_v * s_v + s_b * s_b;
      const double r = hit.depth_m - d;
      ratio[others[i]].push_back(r * r / total);
      share[others[i]].push_back(s_v * s_v / total);
    }
  };
  // The grid is visited in patches of kPatchSamples x kPatchSamples samples (core/patch_grid.h); the medians below
  // do not depend on the order of the samples.
  constexpr int kPatchSamples = 8;
  const int step =
      options.max_samples_per_view <= 0
          ? options.sample_step_px
          : std::max(options.sample_step_px,
                     static_cast<int>(std::ceil(std::sqrt(static_cast<double>(depth.num_pixels()) /
                                                          options.max_samples_per_view))));
  const PatchGrid grid(depth.height, depth.width, kPatchSamples * step, kPatchSamples * step);
  for (int p = 0; p < grid.size(); ++p) {
    const PixelWindow patch = grid.Patch(p);
    for (int row = patch.row_begin + step / 2; row < patch.row_end; row += step) {
      for (int col = patch.col_begin + step / 2; col < patch.col_end; col += step) add_sample(row, col);
    }
  }
  std::vector<PairRow> rows;
  for (uint32_t b = 0; b < views.size(); ++b) {
    if (static_cast<int>(ratio[b].size()) < options.min_samples) continue;
    PairRow r;
    r.v = v;
    r.b = b;
    r.m = UpperMedianInPlace(&ratio[b]) / kMedianChiSquare1;
    r.a = UpperMedianInPlace(&share[b]);
    rows.push_back(r);
  }
  return rows;
}

// One estimate of k (see the header); `prior_k` as in PairRowsOf. Empty when no pair has enough samples.
std::vector<double> EstimatePass(const std::vector<SacView>& views, const ConsultedViews& combine_views,
                                 const ViewNoiseOptions& options, const std::vector<double>& prior_k) {
  const size_t n = views.size();
  std::vector<std::vector<PairRow>> per_view(n);
  tbb::parallel_for(size_t{0}, n, [&](size_t v) {
    per_view[v] = PairRowsOf(views, static_cast<uint32_t>(v), combine_views, options, prior_k);
  });
  // Normal equations of: sum over rows (a x_v + (1 - a) x_b - m)^2 + kMeanPull sum_v (x_v - mean x)^2.
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  size_t num_rows = 0;
  for (const auto& rows : per_view) {
    for (const PairRow& r : rows) {
      const double c[2] = {r.a, 1.0 - r.a};
      const uint32_t idx[2] = {r.v, r.b};
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) normal(idx[i], idx[j]) += c[i] * c[j];
        rhs(idx[i]) += c[i] * r.m;
      }
      ++num_rows;
    }
  }
  if (num_rows == 0) return {};
  const Eigen::MatrixXd centering =
      Eigen::MatrixXd::Identity(n, n) - Eigen::MatrixXd::Constant(n, n, 1.0 / static_cast<double>(n));
  normal += kMeanPull * centering.transpose() * centering;
  // Views in no row: pinned to the mean of the others by the pull alone; a tiny ridge keeps the system regular.
  normal += 1e-9 * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd x = normal.ldlt().solve(rhs);
  std::vector<double> sorted;
  for (size_t v = 0; v < n; ++v) sorted.push_back(std::sqrt(std::max(x(v), 1e-12)));
  std::vector<double> copy = sorted;
  const double median = UpperMedianInPlace(&copy);
  if (!(median > 0) || !std::isfinite(median)) return {};
  std::vector<double> k(n);
  for (size_t v = 0; v < n; ++v) k[v] = std::clamp(sorted[v], 0.1 * median, 10.0 * median);
  return k;
}

}  // namespace

std::vector<double> EstimateViewNoiseFactors(const std::vector<SacView>& views, const ConsultedViews& combine_views,
                                             const ViewNoiseOptions& options) {
  const std::vector<double> ones(views.size(), 1.0);
  if (views.size() < 2) return ones;
  std::vector<double> k = EstimatePass(views, combine_views, options, {});
  if (k.empty()) return ones;
  if (options.slope_step_sigmas > 0) {
    std::vector<double> refined = EstimatePass(views, combine_views, options, k);
    if (!refined.empty()) k = std::move(refined);
  }
  return k;
}

}  // namespace sacfuse
