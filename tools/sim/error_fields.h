#pragma once
// Random fields for the depth error models, all pure functions of their key (deterministic under OpenMP).
#include <cstdint>
#include <vector>

namespace sacfuse::sim {

// Spatially correlated unit Gaussian field, row-major w x h: white N(0, 1) noise blurred with a Gaussian of
// `sigma_px` pixels and divided by the kernel's L2 norm, so every value is again N(0, 1) (sigma_px < 0.3: white).
std::vector<float> CorrelatedGaussianField(int width, int height, double sigma_px, uint64_t key);

// Smooth low-frequency field: b(u, v) = sum_k w_k cos(2 pi (fu_k u + fv_k v) + phase_k) with u, v in [0, 1]
// across the image and sum_k |w_k| = 1, so |b| <= 1.
struct CosineMode {
  double fu = 0.0, fv = 0.0;  // cycles per image width / height
  double phase = 0.0;         // radians
  double weight = 0.0;
};
std::vector<CosineMode> DrawCosineModes(uint64_t key, int count, double max_cycles);
double EvalCosineModes(const std::vector<CosineMode>& modes, double u, double v);

// Inverse of the standard normal CDF (Acklam's rational approximation, |error| < 1.2e-9), p in (0, 1).
double InverseNormalCdf(double p);

}  // namespace sacfuse::sim
