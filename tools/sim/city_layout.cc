#include "tools/sim/city_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tools/sim/noise.h"
#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {
constexpr double kNegInf = -std::numeric_limits<double>::infinity();

// sin(x) to ~1e-7 absolute, a few times faster than libm (the terrain is evaluated for every height sample).
// Deterministic: plain arithmetic only.
double FastSin(double x) {
  double y = x - 2.0 * M_PI * std::nearbyint(x * (0.5 / M_PI));  // [-pi, pi]
  if (y > 0.5 * M_PI) y = M_PI - y;
  if (y < -0.5 * M_PI) y = -M_PI - y;
  const double y2 = y * y;
  return y * (1.0 + y2 * (-1.0 / 6 + y2 * (1.0 / 120 + y2 * (-1.0 / 5040 + y2 * (1.0 / 362880 - y2 / 39916800)))));
}
}  // namespace

double Terrain::Height(double dx, double dy) const {
  double z = ground_z + gx * dx + gy * dy;
  for (const Wave& w : waves) z += w.amplitude * FastSin(w.kx * dx + w.ky * dy + w.phase);
  return z;
}

void Terrain::Range(double dx0, double dy0, double dx1, double dy1, double* lo, double* hi) const {
  const double plane_lo = std::min(gx * dx0, gx * dx1) + std::min(gy * dy0, gy * dy1);
  const double plane_hi = std::max(gx * dx0, gx * dx1) + std::max(gy * dy0, gy * dy1);
  double wave = 0.0;
  for (const Wave& w : waves) wave += std::abs(w.amplitude);
  *lo = ground_z + plane_lo - wave;
  *hi = ground_z + plane_hi + wave;
}

void Building::ToLocal(double u, double v, double* a, double* b) const {
  if (a_along_v) {
    *a = v - cv;
    *b = -(u - cu);
  } else {
    *a = u - cu;
    *b = v - cv;
  }
}

double Building::HeightAt(double u, double v) const {
  double a, b;
  ToLocal(u, v, &a, &b);
  const double da = half_a - std::abs(a);
  const double db = half_b - std::abs(b);
  if (da < 0.0 || db < 0.0) return kNegInf;
  const double eaves = base_z + eaves_h;
  switch (roof) {
    case RoofType::kFlat:
      return eaves + ((parapet_h > 0.0 && std::min(da, db) < parapet_w) ? parapet_h : 0.0);
    case RoofType::kGabled:
      return eaves + db * pitch_tan;
    case RoofType::kHipped:
      return eaves + std::min(da, db) * pitch_tan;
  }
  return eaves;
}

double Building::Top() const {
  switch (roof) {
    case RoofType::kFlat:
      return base_z + eaves_h + parapet_h;
    case RoofType::kGabled:
      return base_z + eaves_h + half_b * pitch_tan;
    case RoofType::kHipped:
      return base_z + eaves_h + std::min(half_a, half_b) * pitch_tan;
  }
  return base_z + eaves_h;
}

void Building::BoundsUV(double* u0, double* v0, double* u1, double* v1) const {
  const double hu = a_along_v ? half_b : half_a;
  const double hv = a_along_v ? half_a : half_b;
  *u0 = cu - hu;
  *u1 = cu + hu;
  *v0 = cv - hv;
  *v1 = cv + hv;
}

double Tree::HeightAt(double u, double v, uint64_t scene_seed) const {
  const double du = u - cu, dv = v - cv;
  const double d2 = (du * du + dv * dv) / (radius * radius);
  if (d2 > 1.0) return kNegInf;
  const double dome = std::sqrt(1.0 - d2);
  // Low-frequency bumps (wavelength ~1.8 m), fading toward the rim: the canopy stays smooth at the sampling scale.
  const double bumps = 0.35 * ValueNoise(HashCombine(scene_seed, seed), du / 1.8, dv / 1.8) * (1.0 - d2);
  return base_z + crown_base_h + (top_h - crown_base_h) * dome + bumps;
}

double CityLayout::TerrainAtCity(double u, double v) const {
  const double dx = cos_r * u - sin_r * v;
  const double dy = sin_r * u + cos_r * v;
  return terrain.Height(dx, dy);
}

int CityLayout::BandAt(const std::vector<RoadBand>& bands, double w, int* interval) {
  const auto it = std::lower_bound(bands.begin(), bands.end(), w,
                                   [](const RoadBand& band, double value) { return band.hi < value; });
  const int idx = static_cast<int>(it - bands.begin());
  if (interval != nullptr) *interval = idx;
  if (it != bands.end() && it->lo <= w) return idx;
  return -1;
}

BlockType CityLayout::BlockAt(int iu, int iv) const {
  const int nu = static_cast<int>(roads_u.size()) + 1;
  const int nv = static_cast<int>(roads_v.size()) + 1;
  if (iu < 0 || iv < 0 || iu >= nu || iv >= nv) return BlockType::kPark;
  return blocks[static_cast<size_t>(iv) * nu + iu];
}

}  // namespace sacfuse::sim
