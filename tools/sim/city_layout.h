#pragma once
// The procedural city as data: terrain, a street grid, blocks, buildings and trees. Everything is laid out in the
// CITY frame (u, v): metres from the area centre, rotated by `rotation_deg` against east, so streets are
// axis-aligned in (u, v). Heights are world z (metres).
#include <cstdint>
#include <functional>
#include <vector>

namespace sacfuse::sim {

// Gently sloped, undulating terrain: z = ground + gx*dx + gy*dy + sum_k a_k sin(kx_k*dx + ky_k*dy + phase_k), with
// (dx, dy) metres from the area centre.
struct Terrain {
  double ground_z = 100.0;
  double gx = 0.0, gy = 0.0;  // slope, metres per metre
  struct Wave {
    double amplitude, kx, ky, phase;
  };
  std::vector<Wave> waves;

  double Height(double dx, double dy) const;
  // Conservative range over [dx0, dx1] x [dy0, dy1].
  void Range(double dx0, double dy0, double dx1, double dy1, double* lo, double* hi) const;
};

enum class RoofType : uint8_t { kFlat, kGabled, kHipped };
enum class BlockType : uint8_t { kPark, kResidential, kUrban, kCommercial };

// A rectangular building, 2.5D: vertical walls from the terrain up to the roof. Its local frame (a, b) has a along
// the ridge: a = u - cu, b = v - cv when !a_along_v, else a = v - cv, b = -(u - cu).
struct Building {
  double cu = 0.0, cv = 0.0;       // centre, city frame, metres
  double half_a = 5.0, half_b = 4.0;  // half length along the ridge axis and across it, metres
  bool a_along_v = false;
  RoofType roof = RoofType::kFlat;
  double base_z = 0.0;             // world z of the ground floor (terrain at the centre), metres
  double eaves_h = 6.0;            // wall height above base_z, metres
  double pitch_tan = 0.0;          // roof slope of gabled/hipped roofs
  double parapet_h = 0.0;          // flat roofs: parapet height, metres (0 = none)
  double parapet_w = 0.3;          // parapet width, metres
  bool rooftop = false;            // a structure on another building's roof (stairwell, HVAC box)
  bool solar = false;              // solar panels on the roof
  uint8_t roof_material = 0;       // index into the roof palette
  uint8_t facade_material = 0;     // index into the façade palette
  double floor_h = 3.0;            // storey height, metres (window rows)
  double window_pitch = 3.0;       // window spacing along the wall, metres
  uint32_t seed = 0;               // per-building texture seed

  void ToLocal(double u, double v, double* a, double* b) const;
  // World z of the roof at (u, v), or -inf outside the footprint.
  double HeightAt(double u, double v) const;
  double Top() const;
  void BoundsUV(double* u0, double* v0, double* u1, double* v1) const;
};

// A round canopy: z = base + crown_base_h + (top_h - crown_base_h) * sqrt(1 - (d / radius)^2) (+ small bumps),
// trunks are hidden under the canopy in 2.5D.
struct Tree {
  double cu = 0.0, cv = 0.0;
  double radius = 3.0;
  double base_z = 0.0;
  double crown_base_h = 3.0;
  double top_h = 10.0;
  uint32_t seed = 0;

  double HeightAt(double u, double v, uint64_t scene_seed) const;  // -inf outside the canopy
  double Top() const { return base_z + top_h + 0.4; }
};

// A road band of constant u (running along v) or constant v, including its sidewalks.
struct RoadBand {
  double lo = 0.0, hi = 0.0;  // metres along the perpendicular axis
  double sidewalk = 2.5;      // sidewalk width on each side, metres
};

struct CityLayout {
  double cx = 0.0, cy = 0.0;    // world position of the city-frame origin (the area centre)
  double cos_r = 1.0, sin_r = 0.0;
  double half_extent = 100.0;   // the layout covers |u|, |v| <= half_extent
  uint64_t seed = 1;
  Terrain terrain;
  std::vector<RoadBand> roads_u;  // bands of u (roads running along v), sorted
  std::vector<RoadBand> roads_v;  // bands of v (roads running along u), sorted
  std::vector<BlockType> blocks;  // (roads_u.size() + 1) x (roads_v.size() + 1), index iv * (nu + 1) + iu
  std::vector<Building> buildings;
  std::vector<Tree> trees;

  void WorldToCity(double x, double y, double* u, double* v) const {
    const double dx = x - cx, dy = y - cy;
    *u = cos_r * dx + sin_r * dy;
    *v = -sin_r * dx + cos_r * dy;
  }
  void CityToWorld(double u, double v, double* x, double* y) const {
    *x = cx + cos_r * u - sin_r * v;
    *y = cy + sin_r * u + cos_r * v;
  }
  double TerrainAtCity(double u, double v) const;
  // Index of the road band containing w (or -1), and the block interval index (number of bands below w).
  static int BandAt(const std::vector<RoadBand>& bands, double w, int* interval);
  BlockType BlockAt(int iu, int iv) const;
};

struct CityParams {
  double area_width_m = 60.0;
  double area_height_m = 60.0;
  double center_x = 0.0, center_y = 0.0;
  double ground_z = 100.0;
  double rotation_deg = 15.0;
  double margin_m = 60.0;  // the city extends this far beyond the area (obliques look outside it)
  uint64_t seed = 1;
};

CityLayout GenerateCityLayout(const CityParams& params);

}  // namespace sacfuse::sim
