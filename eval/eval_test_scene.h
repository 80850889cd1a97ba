#pragma once
// Synthetic scenes for the eval tests: a 40 x 40 m ground plane with buildings, sampled like airborne LiDAR
// (a regular grid, roofs and ground only, no walls) or like a photogrammetric result (random, denser, noisy).
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

namespace sacfuse::eval_test {

struct Building {
  double x0, y0, x1, y1;  // footprint [x0, x1) x [y0, y1), metres
  double eave_m;          // wall height
  double ridge_m = 0.0;   // ridge height above the eaves (0 = flat roof)
  bool ridge_along_x = true;
};

struct Scene {
  double size_m = 40.0;
  std::vector<Building> buildings;

  const Building* BuildingAt(double x, double y) const {
    for (const auto& b : buildings) {
      if (x >= b.x0 && x < b.x1 && y >= b.y0 && y < b.y1) return &b;
    }
    return nullptr;
  }
  // Height of the top surface (roof or ground).
  double HeightAt(double x, double y) const {
    const Building* b = BuildingAt(x, y);
    if (b == nullptr) return 0.0;
    if (b->ridge_m == 0.0) return b->eave_m;
    // Gable: linear from the eaves to the ridge in the middle, across the ridge direction.
    const double u = b->ridge_along_x ? y : x;
    const double lo = b->ridge_along_x ? b->y0 : b->x0, hi = b->ridge_along_x ? b->y1 : b->x1;
    const double half = 0.5 * (hi - lo);
    return b->eave_m + b->ridge_m * (1.0 - std::abs(u - (lo + half)) / half);
  }
};

// One 10 m flat-roofed box, footprint 15.0 .. 24.9 m on the 0.3 m grid (34 x 34 roof points).
inline Scene BoxScene() {
  Scene s;
  s.buildings.push_back({14.95, 14.95, 24.95, 24.95, 10.0});
  return s;
}

// Two gabled houses with orthogonal ridges and a flat box: constrains all six ICP degrees of freedom.
inline Scene GableScene() {
  Scene s;
  s.buildings.push_back({4.0, 5.0, 16.0, 15.0, 6.0, 3.0, true});
  s.buildings.push_back({22.0, 4.0, 32.0, 18.0, 7.0, 3.5, false});
  s.buildings.push_back({8.0, 24.0, 18.0, 34.0, 9.0, 2.5, false});
  s.buildings.push_back({24.0, 24.0, 34.0, 32.0, 10.0});
  return s;
}

// LiDAR-like reference: a regular grid of `spacing` over the scene, one return each, on the top surface.
inline std::vector<Eigen::Vector3d> SampleGrid(const Scene& scene, double spacing = 0.3) {
  std::vector<Eigen::Vector3d> out;
  const int n = static_cast<int>(std::floor(scene.size_m / spacing + 1e-9));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = i * spacing, y = j * spacing;
      out.emplace_back(x, y, scene.HeightAt(x, y));
    }
  }
  return out;
}

// Photogrammetry-like result: uniform random XY at `density` points/m2, top surface plus Gaussian z noise.
inline std::vector<Eigen::Vector3d> SampleRandom(const Scene& scene, double density, double noise_sigma_m,
                                                 uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, scene.size_m);
  std::normal_distribution<double> g(0.0, noise_sigma_m);
  const size_t n = static_cast<size_t>(density * scene.size_m * scene.size_m);
  std::vector<Eigen::Vector3d> out(n);
  for (auto& p : out) {
    const double x = u(rng), y = u(rng);
    p = Eigen::Vector3d(x, y, scene.HeightAt(x, y) + (noise_sigma_m > 0.0 ? g(rng) : 0.0));
  }
  return out;
}

inline std::vector<Eigen::Vector3d> Shifted(std::vector<Eigen::Vector3d> points, const Eigen::Vector3d& shift) {
  for (auto& p : points) p += shift;
  return points;
}

}  // namespace sacfuse::eval_test
