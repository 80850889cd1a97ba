#include "tools/sim/noise.h"

#include <cmath>

#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {

double Lattice(uint64_t seed, int64_t i, int64_t j) {
  return 2.0 * HashToUnit(Hash3(seed, static_cast<uint64_t>(i), static_cast<uint64_t>(j))) - 1.0;
}

double Quintic(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

}  // namespace

double ValueNoise(uint64_t seed, double x, double y) {
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const auto i = static_cast<int64_t>(fx);
  const auto j = static_cast<int64_t>(fy);
  const double tx = Quintic(x - fx);
  const double ty = Quintic(y - fy);
  const double a = Lattice(seed, i, j);
  const double b = Lattice(seed, i + 1, j);
  const double c = Lattice(seed, i, j + 1);
  const double d = Lattice(seed, i + 1, j + 1);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

double Fbm(uint64_t seed, double x, double y, double wavelength, int octaves, double gain) {
  double sum = 0.0;
  double norm = 0.0;
  double amplitude = 1.0;
  double frequency = 1.0 / wavelength;
  for (int k = 0; k < octaves; ++k) {
    // Each octave is shifted so that lattice points of different octaves do not line up.
    sum += amplitude * ValueNoise(HashCombine(seed, k), x * frequency + 0.37 * k, y * frequency - 0.61 * k);
    norm += amplitude;
    amplitude *= gain;
    frequency *= 2.0;
  }
  return norm > 0.0 ? sum / norm : 0.0;
}

double CellHash(uint64_t seed, int64_t i, int64_t j) {
  return HashToUnit(Hash3(seed ^ 0x5bd1e995ULL, static_cast<uint64_t>(i), static_cast<uint64_t>(j)));
}

}  // namespace sacfuse::sim
