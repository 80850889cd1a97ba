#pragma once
// Least-squares intersection of several rays (multi-ray triangulation, as photogrammetric forward intersection
// with more than two rays [35]), optionally with each ray's measured depth as a weak observation along it.
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

struct TriangulationRay {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();     // camera centre, world metres
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ(); // unit vector
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();   // the ray's measured point (origin + depth along it)
  double lateral_sigma_m = 1.0;  // uncertainty across the ray at the point (pixel footprint), metres. > 0
  double along_sigma_m = 0.0;    // uncertainty of the measured point along the ray, metres; 0 = rays only
};

// The point X minimising  sum_k |(I - r_k r_k^T)(X - m_k)|^2 / lateral_k^2 + (r_k . (X - m_k))^2 / along_k^2
// (the second term only where along_sigma_m > 0): with along terms off, the classic multi-ray intersection (the
// point nearest to all rays, each weighted by its precision across); with them, the maximum-likelihood point of
// depth measurements that are precise across their rays and less so along them. nullopt when the system is
// singular (fewer than two non-parallel rays and no along terms).
std::optional<Eigen::Vector3d> TriangulateRays(const std::vector<TriangulationRay>& rays);

}  // namespace sacfuse
