#include "tools/sim/city_texture.h"

#include <algorithm>
#include <cmath>

#include "tools/sim/noise.h"
#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {

using Rgb = Eigen::Vector3f;

const Rgb kRoofPalette[] = {
    {0.58f, 0.27f, 0.18f},  // 0 terracotta
    {0.36f, 0.25f, 0.19f},  // 1 dark brown
    {0.21f, 0.21f, 0.23f},  // 2 anthracite
    {0.35f, 0.37f, 0.42f},  // 3 slate grey
    {0.48f, 0.22f, 0.17f},  // 4 red-brown
    {0.62f, 0.60f, 0.56f},  // 5 gravel (flat)
    {0.20f, 0.20f, 0.21f},  // 6 bitumen (flat)
    {0.26f, 0.38f, 0.17f},  // 7 green roof (flat)
    {0.70f, 0.70f, 0.68f},  // 8 light concrete (flat, rooftop boxes)
};
const Rgb kFacadePalette[] = {
    {0.80f, 0.74f, 0.62f},  // 0 beige plaster
    {0.88f, 0.87f, 0.84f},  // 1 white
    {0.66f, 0.66f, 0.66f},  // 2 light grey
    {0.58f, 0.30f, 0.22f},  // 3 brick
    {0.82f, 0.68f, 0.42f},  // 4 ochre
    {0.34f, 0.35f, 0.37f},  // 5 dark grey (modern)
    {0.62f, 0.68f, 0.74f},  // 6 pale blue-grey
};
const Rgb kPanel(0.07f, 0.09f, 0.18f);
const Rgb kPanelFrame(0.55f, 0.56f, 0.58f);
const Rgb kWhite(0.86f, 0.86f, 0.84f);

double Frac(double x) { return x - std::floor(x); }
float Vary(uint64_t seed, double amount) { return static_cast<float>(1.0 + amount * (2.0 * HashToUnit(seed) - 1.0)); }
Rgb Clamp(const Rgb& c) { return c.cwiseMax(0.0f).cwiseMin(1.0f); }

// Solar panels in a grid with frames: returns true and the colour when (x, y) is on the array.
bool Panels(double x, double y, double cell_x, double cell_y, Rgb* out) {
  const double fx = Frac(x / cell_x) * cell_x, fy = Frac(y / cell_y) * cell_y;
  const bool frame = fx < 0.06 || fy < 0.06;
  *out = frame ? kPanelFrame : kPanel;
  return true;
}

Rgb Grass(uint64_t seed, double u, double v) {
  const double n = Fbm(seed, u, v, 4.0, 4);
  Rgb c = Rgb(0.28f, 0.42f, 0.16f) * static_cast<float>(0.85 + 0.3 * n);
  const double patch = Fbm(seed + 1, u, v, 18.0, 2);
  if (patch > 0.45) c = c * 0.5f + Rgb(0.42f, 0.36f, 0.25f) * 0.5f;  // worn patches
  return c;
}

Rgb Asphalt(uint64_t seed, double u, double v, float base) {
  const double n = 0.04 * Fbm(seed + 2, u, v, 6.0, 3) + 0.03 * (CellHash(seed, std::floor(u / 0.2), std::floor(v / 0.2)) - 0.5);
  const float g = static_cast<float>(base + n);
  return Rgb(g, g, g * 1.03f);
}

Rgb Paving(uint64_t seed, double u, double v, double slab) {
  const double h = CellHash(seed + 3, std::floor(u / slab), std::floor(v / slab));
  const float g = static_cast<float>(0.47 + 0.08 * h);
  return Rgb(g, g * 0.98f, g * 0.95f);
}

// Carriageway of a road band: `across` from the band's low edge, `along` the road; markings and zebra crossings.
Rgb Road(uint64_t seed, const RoadBand& band, double across, double along, const std::vector<RoadBand>& crossing,
         double u, double v) {
  const double width = band.hi - band.lo;
  if (across < band.sidewalk || across > width - band.sidewalk) {
    const double kerb = std::min(std::abs(across - band.sidewalk), std::abs(across - (width - band.sidewalk)));
    if (kerb < 0.25) return Rgb(0.66f, 0.66f, 0.64f);
    return Paving(seed, u, v, 0.6);
  }
  // Zebra crossings 1-5 m before a crossing road.
  int interval = 0;
  CityLayout::BandAt(crossing, along, &interval);
  const double below = interval > 0 ? along - crossing[interval - 1].hi : 1e9;
  const double above = interval < static_cast<int>(crossing.size()) ? crossing[interval].lo - along : 1e9;
  const double to_crossing = std::min(below, above);
  if (to_crossing > 1.0 && to_crossing < 5.0) {
    if (Frac((across - band.sidewalk) / 1.0) < 0.5) return kWhite;
    return Asphalt(seed, u, v, 0.25f);
  }
  const double centre = 0.5 * width;
  if (std::abs(across - centre) < 0.1 && Frac(along / 9.0) < 0.34 && to_crossing > 5.0) return kWhite;
  const double edge_lo = band.sidewalk + 0.45, edge_hi = width - band.sidewalk - 0.45;
  if ((std::abs(across - edge_lo) < 0.08 || std::abs(across - edge_hi) < 0.08) && to_crossing > 5.0) {
    return kWhite * 0.95f;
  }
  return Asphalt(seed, u, v, 0.25f);
}

}  // namespace

Rgb RoofAlbedo(const Building& b, double a, double bb, uint64_t seed) {
  const uint64_t bs = HashCombine(seed, b.seed);
  Rgb base = kRoofPalette[std::min<int>(b.roof_material, 8)] * Vary(bs, 0.12);
  const double da = b.half_a - std::abs(a), db = b.half_b - std::abs(bb);
  const double weather = 0.1 * Fbm(bs, a, bb, 3.0, 3);
  if (b.roof == RoofType::kFlat) {
    if (b.parapet_h > 0.0 && std::min(da, db) < b.parapet_w) return Clamp(Rgb(0.72f, 0.71f, 0.69f) * Vary(bs + 5, 0.05));
    Rgb panel;
    if (b.solar && da > 2.0 && db > 2.0 && Frac((bb + b.half_b) / 2.6) < 0.5 &&
        Panels(a + b.half_a, bb + b.half_b, 1.05, 1.3, &panel)) {
      return panel;
    }
    const double speckle = 0.05 * (CellHash(bs, std::floor(a / 0.25), std::floor(bb / 0.25)) - 0.5);
    return Clamp(base * static_cast<float>(1.0 + 1.2 * weather + speckle));
  }
  // Pitched: q = distance from the eaves up the slope, r = coordinate along the tile rows.
  const bool across = b.roof == RoofType::kGabled || db <= da;
  const double q = across ? db : da;
  const double r = across ? a : bb;
  if (q < 0.12) return Clamp(base * 0.7f);  // gutter line at the eaves
  if (b.roof == RoofType::kGabled && std::abs(bb) < 0.18) return Clamp(base * 0.78f);  // ridge tiles
  if (b.roof == RoofType::kHipped && std::abs(da - db) < 0.12) return Clamp(base * 0.8f);  // hips
  Rgb panel;
  if (b.solar && bb > 0.0 && across && da > 1.0 && q > 0.8 && q < b.half_b - 0.8 &&
      Panels(r + b.half_a, q, 1.05, 1.7, &panel)) {
    return panel;
  }
  const int row = static_cast<int>(std::floor(q / 0.42));
  const double row_shade = Frac(q / 0.42) < 0.22 ? 0.84 : 1.0;
  const double col_shade = Frac((r + 0.15 * (row & 1)) / 0.3) < 0.12 ? 0.94 : 1.0;
  return Clamp(base * static_cast<float>(row_shade * col_shade * (1.0 + weather)));
}

Rgb FacadeAlbedo(const Building& b, double along, double h, uint64_t seed) {
  const uint64_t bs = HashCombine(seed, b.seed);
  Rgb wall = kFacadePalette[std::min<int>(b.facade_material, 6)] * Vary(bs + 7, 0.08);
  wall *= static_cast<float>(1.0 + 0.05 * Fbm(bs + 8, along, h, 2.5, 3));
  if (b.rooftop) return Clamp(wall * 0.9f);
  if (h > b.eaves_h - 0.6 || h < 0.3) return Clamp(wall * 0.82f);  // cornice and plinth bands
  const int floor = static_cast<int>(std::floor(h / b.floor_h));
  const double y = h - floor * b.floor_h;
  const double window_w = std::min(1.3, 0.55 * b.window_pitch);
  const double x = along - 0.5 * b.window_pitch;
  const int column = static_cast<int>(std::floor(x / b.window_pitch + 0.5));
  const double dx = std::abs(x - column * b.window_pitch);
  const double y0 = floor == 0 ? 0.5 : 0.9, y1 = floor == 0 ? 2.5 : 2.35;
  if (dx < 0.5 * window_w && y > y0 && y < y1) {
    const bool frame = dx > 0.5 * window_w - 0.08 || y < y0 + 0.08 || y > y1 - 0.08;
    if (frame) return Rgb(0.82f, 0.82f, 0.8f);
    const float g = static_cast<float>(0.75 + 0.6 * CellHash(bs, column, floor));
    return Clamp(Rgb(0.11f, 0.14f, 0.19f) * g);
  }
  return Clamp(wall);
}

Rgb TreeAlbedo(const Tree& t, double u, double v, uint64_t seed) {
  const uint64_t ts = HashCombine(seed, t.seed);
  const Rgb base(static_cast<float>(0.12 + 0.09 * HashToUnit(ts)), static_cast<float>(0.25 + 0.11 * HashToUnit(ts + 1)),
                 static_cast<float>(0.08 + 0.06 * HashToUnit(ts + 2)));
  const double du = u - t.cu, dv = v - t.cv;
  const double clusters = Fbm(ts, du, dv, 1.4, 3);
  const double leaves = ValueNoise(ts + 3, du / 0.35, dv / 0.35);
  const double rim = std::sqrt(std::max(0.0, 1.0 - (du * du + dv * dv) / (t.radius * t.radius)));
  return Clamp(base * static_cast<float>((0.75 + 0.35 * clusters + 0.12 * leaves) * (0.8 + 0.25 * rim)));
}

Rgb GroundAlbedo(const CityLayout& L, double u, double v, uint64_t seed) {
  int iu = 0, iv = 0;
  const int bu = CityLayout::BandAt(L.roads_u, u, &iu);
  const int bv = CityLayout::BandAt(L.roads_v, v, &iv);
  if (bu >= 0 && bv >= 0) {  // intersection: sidewalk corners, asphalt elsewhere
    const RoadBand& a = L.roads_u[bu];
    const RoadBand& b = L.roads_v[bv];
    const bool side_u = u - a.lo < a.sidewalk || a.hi - u < a.sidewalk;
    const bool side_v = v - b.lo < b.sidewalk || b.hi - v < b.sidewalk;
    return side_u && side_v ? Paving(seed, u, v, 0.6) : Asphalt(seed, u, v, 0.25f);
  }
  if (bu >= 0) return Road(seed, L.roads_u[bu], u - L.roads_u[bu].lo, v, L.roads_v, u, v);
  if (bv >= 0) return Road(seed, L.roads_v[bv], v - L.roads_v[bv].lo, u, L.roads_u, u, v);
  const double far = 1e9;
  const double u0 = iu > 0 ? L.roads_u[iu - 1].hi : -far, u1 = iu < static_cast<int>(L.roads_u.size()) ? L.roads_u[iu].lo : far;
  const double v0 = iv > 0 ? L.roads_v[iv - 1].hi : -far, v1 = iv < static_cast<int>(L.roads_v.size()) ? L.roads_v[iv].lo : far;
  switch (L.BlockAt(iu, iv)) {
    case BlockType::kPark: {
      const bool s_along_u = (u1 - u0) >= (v1 - v0);
      const double t = s_along_u ? v - 0.5 * (v0 + v1) : u - 0.5 * (u0 + u1);
      if (std::abs(t) < 1.6 && (u1 - u0) < far && (v1 - v0) < far) {
        const double g = 0.05 * (CellHash(seed + 4, std::floor(u / 0.15), std::floor(v / 0.15)) - 0.5);
        return Clamp(Rgb(0.58f, 0.52f, 0.42f) * static_cast<float>(1.0 + g));
      }
      return Grass(seed, u, v);
    }
    case BlockType::kResidential:
      return Grass(seed, u, v);
    case BlockType::kUrban:
      return HashToUnit(Hash3(seed, iu, iv)) < 0.5 ? Paving(seed, u, v, 0.8) : Grass(seed, u, v);
    case BlockType::kCommercial: {
      const double su = u - u0, sv = v - v0;
      if (Frac(su / 2.5) < 0.05 && Frac(sv / 13.0) > 0.08 && Frac(sv / 13.0) < 0.46) return kWhite;
      return Asphalt(seed, u, v, 0.3f);
    }
  }
  return Grass(seed, u, v);
}

}  // namespace sacfuse::sim
