#include "eval/robust_icp.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sacfuse {
namespace {

constexpr int kNormalNeighbours = 10;

// Unit normal of the reference around point i: smallest-eigenvalue direction of its neighbourhood covariance.
Eigen::Vector3f ReferenceNormal(const std::vector<Eigen::Vector3f>& reference, const PointIndex& index, uint32_t i) {
  uint32_t idx[kNormalNeighbours];
  float d2[kNormalNeighbours];
  const size_t n = index.Knn(reference[i], kNormalNeighbours, idx, d2);
  if (n < 3) return Eigen::Vector3f::UnitZ();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < n; ++k) mean += reference[idx[k]].cast<double>();
  mean /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d d = reference[idx[k]].cast<double>() - mean;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  Eigen::Vector3d normal = eig.eigenvectors().col(0);
  if (!normal.allFinite() || normal.norm() < 0.5) return Eigen::Vector3f::UnitZ();
  return normal.normalized().cast<float>();
}

// Rigid update from weighted pairs (q -> m), point to plane: linearised rotation about `centre`, damped so that
// directions the geometry leaves unconstrained (e.g. sliding along a flat plane) do not move.
Eigen::Matrix4d SolvePointToPlane(const std::vector<Eigen::Vector3d>& q, const std::vector<Eigen::Vector3d>& m,
                                  const std::vector<Eigen::Vector3d>& n, const std::vector<double>& w) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double wsum = 0.0;
  for (size_t i = 0; i < q.size(); ++i) {
    centre += w[i] * q[i];
    wsum += w[i];
  }
  centre /= wsum;
  Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
  for (size_t i = 0; i < q.size(); ++i) {
    Eigen::Matrix<double, 6, 1> j;
    j.head<3>() = (q[i] - centre).cross(n[i]);
    j.tail<3>() = n[i];
    const double r = n[i].dot(q[i] - m[i]);
    a.noalias() += w[i] * j * j.transpose();
    b.noalias() += w[i] * r * j;
  }
  const double damping = 1e-6 * (a.trace() / 6.0) + 1e-12;
  a.diagonal().array() += damping;
  const Eigen::Matrix<double, 6, 1> x = a.ldlt().solve(-b);
  const Eigen::Vector3d omega = x.head<3>();
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
  if (omega.norm() > 0.0) rot = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix();
  Eigen::Matrix4d delta = Eigen::Matrix4d::Identity();
  delta.topLeftCorner<3, 3>() = rot;
  delta.topRightCorner<3, 1>() = centre + x.tail<3>() - rot * centre;
  return delta;
}

// Weighted Kabsch / Umeyama without scale.
Eigen::Matrix4d SolvePointToPoint(const std::vector<Eigen::Vector3d>& q, const std::vector<Eigen::Vector3d>& m,
                                  const std::vector<double>& w) {
  Eigen::Vector3d qc = Eigen::Vector3d::Zero(), mc = Eigen::Vector3d::Zero();
  double wsum = 0.0;
  for (size_t i = 0; i < q.size(); ++i) {
    qc += w[i] * q[i];
    mc += w[i] * m[i];
    wsum += w[i];
  }
  qc /= wsum;
  mc /= wsum;
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < q.size(); ++i) h.noalias() += w[i] * (q[i] - qc) * (m[i] - mc).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d s = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) s(2, 2) = -1.0;
  const Eigen::Matrix3d rot = svd.matrixV() * s * svd.matrixU().transpose();
  Eigen::Matrix4d delta = Eigen::Matrix4d::Identity();
  delta.topLeftCorner<3, 3>() = rot;
  delta.topRightCorner<3, 1>() = mc - rot * qc;
  return delta;
}

}  // namespace

IcpResult AlignRobustIcp(const std::vector<Eigen::Vector3f>& result, const std::vector<uint8_t>* use,
                         const std::vector<Eigen::Vector3f>& reference, const PointIndex& reference_index,
                         const EvalOptions& options) {
  IcpResult out;
  // Seeded subsample (std::sample keeps the input order, so the run is deterministic).
  std::vector<uint32_t> eligible;
  for (size_t i = 0; i < result.size(); ++i) {
    if (use == nullptr || (*use)[i] != 0) eligible.push_back(static_cast<uint32_t>(i));
  }
  const size_t max_points = static_cast<size_t>(options.align_max_points);
  std::vector<uint32_t> chosen;
  if (eligible.size() > max_points) {
    std::mt19937_64 rng(options.align_seed);
    std::sample(eligible.begin(), eligible.end(), std::back_inserter(chosen), max_points, rng);
  } else {
    chosen.swap(eligible);
  }
  std::vector<uint32_t>().swap(eligible);
  if (chosen.size() < 6 || reference_index.size() < 6) return out;

  const bool plane = options.align_mode != "point_to_point";
  const size_t n = chosen.size();
  std::vector<Eigen::Vector3d> src(n);
  for (size_t i = 0; i < n; ++i) src[i] = result[chosen[i]].cast<double>();

  std::vector<uint32_t> match(n);
  std::vector<float> dist(n);
  std::vector<Eigen::Vector3d> moved(n);
  std::unordered_map<uint32_t, Eigen::Vector3f> normals;
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
  const float max_distance = static_cast<float>(options.align_max_distance_m);

  for (int it = 0; it < options.align_max_iterations; ++it) {
    out.iterations = it + 1;
    const Eigen::Matrix3d rot = transform.topLeftCorner<3, 3>();
    const Eigen::Vector3d trans = transform.topRightCorner<3, 1>();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 2048), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        moved[i] = rot * src[i] + trans;
        float d2 = std::numeric_limits<float>::infinity();
        if (!reference_index.Nearest(moved[i].cast<float>(), &match[i], &d2)) {
          d2 = std::numeric_limits<float>::infinity();
        }
        dist[i] = std::sqrt(d2);
      }
    });
    if (plane) {  // normals of newly matched reference points, in parallel
      std::vector<uint32_t> missing;
      for (size_t i = 0; i < n; ++i) {
        if (dist[i] <= max_distance && normals.find(match[i]) == normals.end()) {
          normals.emplace(match[i], Eigen::Vector3f::Zero());
          missing.push_back(match[i]);
        }
      }
      std::vector<Eigen::Vector3f> computed(missing.size());
      tbb::parallel_for(tbb::blocked_range<size_t>(0, missing.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k) {
          computed[k] = ReferenceNormal(reference, reference_index, missing[k]);
        }
      });
      for (size_t k = 0; k < missing.size(); ++k) normals[missing[k]] = computed[k];
    }
    // Residuals of usable pairs, then trimming.
    std::vector<std::pair<double, uint32_t>> pairs;
    pairs.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      if (!(dist[i] <= max_distance)) continue;
      const Eigen::Vector3d m = reference[match[i]].cast<double>();
      const double e = plane ? std::abs(normals[match[i]].cast<double>().dot(moved[i] - m)) : (moved[i] - m).norm();
      pairs.emplace_back(e, static_cast<uint32_t>(i));
    }
    const size_t keep = static_cast<size_t>(std::ceil(options.align_trim_fraction * static_cast<double>(pairs.size())));
    if (keep < 6) break;
    std::nth_element(pairs.begin(), pairs.begin() + (keep - 1), pairs.end());
    pairs.resize(keep);
    std::nth_element(pairs.begin(), pairs.begin() + keep / 2, pairs.end());
    const double sigma = 1.4826 * pairs[keep / 2].first;
    const double huber = std::max(1.345 * sigma, 1e-4);

    std::vector<Eigen::Vector3d> q(keep), m(keep), nn;
    std::vector<double> w(keep);
    if (plane) nn.resize(keep);
    double wr2 = 0.0, wsum = 0.0;
    for (size_t k = 0; k < keep; ++k) {
      const uint32_t i = pairs[k].second;
      q[k] = moved[i];
      m[k] = reference[match[i]].cast<double>();
      if (plane) nn[k] = normals[match[i]].cast<double>();
      const double e = pairs[k].first;
      w[k] = e <= huber ? 1.0 : huber / e;
      wr2 += w[k] * e * e;
      wsum += w[k];
    }
    out.correspondences = keep;
    out.rms_m = std::sqrt(wr2 / wsum);
    const Eigen::Matrix4d delta = plane ? SolvePointToPlane(q, m, nn, w) : SolvePointToPoint(q, m, w);
    transform = delta * transform;

    // Size of the update: displacement of the kept pairs' centroid, and rotation angle.
    const Eigen::Matrix3d drot = delta.topLeftCorner<3, 3>();
    const double angle = Eigen::AngleAxisd(drot).angle();
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& p : q) centre += p;
    centre /= static_cast<double>(keep);
    const double shift = (drot * centre + delta.topRightCorner<3, 1>() - centre).norm();
    if (shift < 1e-4 && angle < 1e-6) {
      out.converged = true;
      break;
    }
  }
  out.result_from_input = transform;
  return out;
}

}  // namespace sacfuse
