#include "eval/eval.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/error.h"
#include "eval/point_index.h"
#include "eval/robust_icp.h"
#include "eval/top_surface.h"
#include "eval/voxel_groups.h"

namespace sacfuse {
namespace {

constexpr uint8_t kIgnored = 0, kMiss = 1, kHit = 2;

template <typename F>
void ParallelFor(size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

// Offsets from `origin` as floats; throws on non-finite input, naming the first such point.
std::vector<Eigen::Vector3f> ToLocal(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                                     const char* what) {
  std::vector<Eigen::Vector3f> local(points.size());
  std::atomic<size_t> first_bad{points.size()};
  ParallelFor(points.size(), [&](size_t i) {
    if (!points[i].allFinite()) {
      size_t known = first_bad.load(std::memory_order_relaxed);
      while (i < known && !first_bad.compare_exchange_weak(known, i, std::memory_order_relaxed)) {
      }
      return;
    }
    local[i] = (points[i] - origin).cast<float>();
  });
  if (first_bad < points.size()) {
    throw Error(std::string(what) + " point " + std::to_string(first_bad.load()) + " has a non-finite coordinate");
  }
  return local;
}

std::vector<uint8_t> MaskFlags(const std::vector<Eigen::Vector3f>& local, const Eigen::Vector3d& origin,
                               const GeoMask* mask) {
  std::vector<uint8_t> in(local.size(), 1);
  if (mask == nullptr) return in;
  ParallelFor(local.size(), [&](size_t i) {
    in[i] = mask->Contains(origin.x() + local[i].x(), origin.y() + local[i].y()) ? 1 : 0;
  });
  return in;
}

// How many outcomes are counted (not ignored) and how many of those are hits.
void CountOutcomes(const std::vector<uint8_t>& outcomes, uint64_t* counted, uint64_t* hits) {
  using Counts = std::pair<uint64_t, uint64_t>;
  const Counts c = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, outcomes.size(), 1 << 16), Counts{0, 0},
      [&](const tbb::blocked_range<size_t>& r, Counts acc) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          acc.first += outcomes[i] != kIgnored;
          acc.second += outcomes[i] == kHit;
        }
        return acc;
      },
      [](Counts a, Counts b) { return Counts{a.first + b.first, a.second + b.second}; });
  *counted = c.first;
  *hits = c.second;
}

double F1(double a, double c) { return a + c > 0.0 ? 2.0 * a * c / (a + c) : 0.0; }

double Median(std::vector<float> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + mid);
  return 0.5 * (lower + upper);
}

// Per reference point, the distance to the nearest of the points offered to it, exact below `radius` (+infinity
// beyond): completeness needs no more than whether that distance is within each threshold, so the reference's
// index answers it and the result cloud needs no index of its own (no serial tree build over millions of points).
// Offer may be called from many threads at once; the distances do not depend on the order.
class NearestWithin {
 public:
  NearestWithin(const PointIndex& reference_index, size_t reference_size, float radius)
      : index_(reference_index), radius_(radius), best_(reference_size) {
    for (auto& b : best_) b.store(std::numeric_limits<float>::infinity(), std::memory_order_relaxed);
  }
  void Offer(const Eigen::Vector3f& p) {
    index_.ForEachWithin(p, radius_, [&](uint32_t j, float squared_distance) {
      const float d = std::sqrt(squared_distance);
      float known = best_[j].load(std::memory_order_relaxed);
      while (d < known && !best_[j].compare_exchange_weak(known, d, std::memory_order_relaxed)) {
      }
    });
  }
  // The distances of the reference points whose `use` flag is set (+infinity for the others).
  std::vector<float> Distances(const std::vector<uint8_t>& use) const {
    std::vector<float> out(best_.size(), std::numeric_limits<float>::infinity());
    ParallelFor(best_.size(), [&](size_t j) {
      if (use[j] != 0) out[j] = best_[j].load(std::memory_order_relaxed);
    });
    return out;
  }

 private:
  const PointIndex& index_;
  float radius_;
  std::vector<std::atomic<float>> best_;
};

// The search radius of completeness for thresholds up to `max_tau`: a little beyond it, so that every point whose
// float distance rounds to max_tau is found (the index compares squared distances strictly).
float CompletenessRadius(double max_tau) { return static_cast<float>(max_tau * 1.001); }

// Completeness distances against a streamed cloud: its points are moved into the local frame (minus `origin`) and
// then by local_from_input (the alignment; identity without one).
std::vector<float> StreamedNearestDistances(const PointIndex& reference_index, size_t reference_size,
                                            const std::vector<uint8_t>& use, const Eigen::Vector3d& origin,
                                            const Eigen::Matrix4d& local_from_input, double max_tau,
                                            const ResultChunks& all_points) {
  NearestWithin nearest(reference_index, reference_size, CompletenessRadius(max_tau));
  const Eigen::Matrix3d rot = local_from_input.topLeftCorner<3, 3>();
  const Eigen::Vector3d trans = local_from_input.topRightCorner<3, 1>();
  all_points([&](const std::vector<Eigen::Vector3d>& chunk) {
    ParallelFor(chunk.size(), [&](size_t i) {
      if (!chunk[i].allFinite()) throw Error("result point has a non-finite coordinate");
      nearest.Offer((rot * (chunk[i] - origin) + trans).cast<float>());
    });
  });
  return nearest.Distances(use);
}

}  // namespace

EvalReport EvaluateClouds(const std::vector<Eigen::Vector3d>& result, const std::vector<uint16_t>& result_source_ids,
                          const std::vector<Eigen::Vector3d>& reference, const GeoMask* mask,
                          const EvalOptions& options, const ResultChunks& all_result_points) {
  ValidateEvalOptions(options);
  if (!result_source_ids.empty() && result_source_ids.size() != result.size()) {
    throw Error("EvaluateClouds: " + std::to_string(result_source_ids.size()) + " source IDs for " +
                std::to_string(result.size()) + " result points");
  }
  if (reference.empty()) throw Error("EvaluateClouds: the reference cloud is empty; nothing to evaluate against");
  const std::vector<double> taus = EvalThresholds(options);
  const double max_tau = *std::max_element(taus.begin(), taus.end());
  const double voxel = EvalVoxelSize(options);

  EvalReport report;
  report.result_points = result.size();
  report.reference_points = reference.size();
  std::vector<uint64_t> per_id(1 << 16, 0);  // counted in an array: a map insert per point was a serial hot spot
  for (const uint16_t id : result_source_ids) ++per_id[id];
  for (size_t id = 0; id < per_id.size(); ++id) {
    if (per_id[id] > 0) report.source_id_histogram[static_cast<uint16_t>(id)] = per_id[id];
  }

  // Local frame: float offsets from the reference's min corner (double).
  Eigen::Vector3d origin = reference[0];
  for (const auto& p : reference) origin = origin.cwiseMin(p);
  const std::vector<Eigen::Vector3f> ref = ToLocal(reference, origin, "reference");
  std::vector<Eigen::Vector3f> res = ToLocal(result, origin, "result");
  const std::vector<uint8_t> ref_in = MaskFlags(ref, origin, mask);
  std::vector<uint8_t> res_in = MaskFlags(res, origin, mask);

  const PointIndex ref_index(ref);
  if (options.align) {
    const IcpResult icp = AlignRobustIcp(res, &res_in, ref, ref_index, options);
    const Eigen::Matrix3d rot = icp.result_from_input.topLeftCorner<3, 3>();
    const Eigen::Vector3d trans = icp.result_from_input.topRightCorner<3, 1>();
    ParallelFor(res.size(), [&](size_t i) { res[i] = (rot * res[i].cast<double>() + trans).cast<float>(); });
    res_in = MaskFlags(res, origin, mask);  // the mask applies where the points are now
    report.aligned = true;
    report.alignment = icp.result_from_input;
    report.alignment.topRightCorner<3, 1>() = trans + origin - rot * origin;  // local -> input CRS
  }

  const TopSurface top(ref, EvalTopCellSize(options));
  const std::vector<float> res_dist = NearestDistances(ref_index, res, &res_in);
  std::vector<float> ref_dist;
  if (all_result_points) {
    // The local frame's alignment: res (local) = rot * (input - origin) + trans, as applied above.
    Eigen::Matrix4d local_from_input = Eigen::Matrix4d::Identity();
    if (report.aligned) {
      const Eigen::Matrix3d rot = report.alignment.topLeftCorner<3, 3>();
      local_from_input.topLeftCorner<3, 3>() = rot;
      local_from_input.topRightCorner<3, 1>() = report.alignment.topRightCorner<3, 1>() - origin + rot * origin;
    }
    ref_dist = StreamedNearestDistances(ref_index, ref.size(), ref_in, origin, local_from_input, max_tau,
                                        all_result_points);
    report.completeness_from_all_points = true;
  } else {
    NearestWithin nearest(ref_index, ref.size(), CompletenessRadius(max_tau));
    ParallelFor(res.size(), [&](size_t i) { nearest.Offer(res[i]); });
    ref_dist = nearest.Distances(ref_in);
  }
  const VoxelGroups res_voxels(res, voxel, &res_in);
  const VoxelGroups ref_voxels(ref, voxel, &ref_in);

  uint64_t res_inside = 0;
  for (uint8_t f : res_in) res_inside += f;
  report.result_points_outside_mask = result.size() - res_inside;

  std::vector<uint8_t> res_out(res.size()), ref_out(ref.size());
  for (size_t t = 0; t < taus.size(); ++t) {
    const double tau = taus[t];
    const double visible_margin = std::max(tau, options.visible_margin_m);
    ParallelFor(res.size(), [&](size_t i) {
      uint8_t o = kIgnored;
      if (res_in[i] != 0) {
        if (res_dist[i] <= tau) {
          o = kHit;
        } else {
          const TopSurface::Column c = top.Query(res[i].x(), res[i].y());
          const double z = res[i].z();
          const bool hidden = z < c.top - tau && z >= c.bottom - tau;
          o = (!c.observed || hidden) ? kIgnored : kMiss;
        }
      }
      res_out[i] = o;
    });
    ParallelFor(ref.size(), [&](size_t i) {
      uint8_t o = kIgnored;
      if (ref_in[i] != 0) {
        const TopSurface::Column c = top.Query(ref[i].x(), ref[i].y());
        if (ref[i].z() >= c.occluder - visible_margin) o = ref_dist[i] <= tau ? kHit : kMiss;
      }
      ref_out[i] = o;
    });

    ThresholdScore s;
    s.tau_m = tau;
    CountOutcomes(res_out, &s.result_observed, &s.result_accurate);
    CountOutcomes(ref_out, &s.reference_visible, &s.reference_complete);
    s.accuracy = res_voxels.CellMean(res_out, &s.accuracy_voxels);
    s.completeness = ref_voxels.CellMean(ref_out, &s.completeness_voxels);
    s.f1 = F1(s.accuracy, s.completeness);
    s.raw_accuracy = s.result_observed > 0 ? static_cast<double>(s.result_accurate) / s.result_observed : 0.0;
    s.raw_completeness =
        s.reference_visible > 0 ? static_cast<double>(s.reference_complete) / s.reference_visible : 0.0;
    s.raw_f1 = F1(s.raw_accuracy, s.raw_completeness);
    report.scores.push_back(s);

    if (t == 0) {  // report-level counts and distances at the smallest threshold
      report.result_points_evaluated = s.result_observed;
      report.result_points_unobserved = res_inside - s.result_observed;
      report.reference_points_evaluated = s.reference_visible;
      std::vector<float> observed;
      observed.reserve(s.result_observed);
      double sum = 0.0;
      for (size_t i = 0; i < res.size(); ++i) {
        if (res_out[i] == kIgnored) continue;
        observed.push_back(res_dist[i]);
        sum += res_dist[i];
      }
      report.mean_abs_distance_m = observed.empty() ? 0.0 : sum / static_cast<double>(observed.size());
      report.median_abs_distance_m = Median(std::move(observed));
    }
  }

  if (mask != nullptr) {
    const auto inside = std::count_if(mask->cells.begin(), mask->cells.end(), [](uint8_t c) { return c != 0; });
    report.area_m2 = static_cast<double>(inside) * mask->cell_size_m * mask->cell_size_m;
  } else {
    report.area_m2 = top.OccupiedArea();
  }
  report.points_per_m2 = report.area_m2 > 0.0 ? static_cast<double>(res_inside) / report.area_m2 : 0.0;
  return report;
}

}  // namespace sacfuse
