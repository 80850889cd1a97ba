// GenerateCityLayout: a seeded street grid with residential, urban (perimeter), commercial and park blocks.
#include <algorithm>
#include <cmath>

#include "tools/sim/city_layout.h"
#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// A block in its own frame: s along the long side, t across, both from the block's corner.
struct BlockFrame {
  double u0, v0;
  double ls, lt;  // lengths along s and t
  bool s_along_u;
  void ToCity(double s, double t, double* u, double* v) const {
    *u = s_along_u ? u0 + s : u0 + t;
    *v = s_along_u ? v0 + t : v0 + s;
  }
};

class Generator {
 public:
  Generator(CityLayout* layout, uint64_t seed) : L_(*layout), rng_(seed) {}

  std::vector<RoadBand> MakeBands() {
    std::vector<RoadBand> bands;
    double w = -L_.half_extent - rng_.Uniform(0.0, 80.0);
    while (w < L_.half_extent) {
      w += rng_.Uniform(50.0, 100.0);  // block length
      const bool main_road = rng_.Bernoulli(0.25);
      const double width = main_road ? rng_.Uniform(18.0, 22.0) : rng_.Uniform(11.0, 15.0);
      bands.push_back({w, w + width, main_road ? 3.5 : 2.5});
      w += width;
    }
    return bands;
  }

  void FillBlock(BlockType type, const BlockFrame& f) {
    switch (type) {
      case BlockType::kPark:
        return FillPark(f);
      case BlockType::kResidential:
        return FillResidential(f);
      case BlockType::kUrban:
        return FillUrban(f);
      case BlockType::kCommercial:
        return FillCommercial(f);
    }
  }

  void StreetTrees() {
    const double e = L_.half_extent;
    for (int dir = 0; dir < 2; ++dir) {
      const auto& bands = dir == 0 ? L_.roads_u : L_.roads_v;
      const auto& cross = dir == 0 ? L_.roads_v : L_.roads_u;
      for (const RoadBand& band : bands) {
        if (!rng_.Bernoulli(0.45)) continue;
        const double spacing = rng_.Uniform(10.0, 14.0);
        const double phase = rng_.Uniform(0.0, spacing);
        for (double along = -e + phase; along < e; along += spacing) {
          bool at_crossing = false;
          for (const RoadBand& c : cross) at_crossing |= along > c.lo - 4.0 && along < c.hi + 4.0;
          if (at_crossing) continue;
          for (const double across : {band.lo + 1.3, band.hi - 1.3}) {
            if (!rng_.Bernoulli(0.85)) continue;
            Tree t;
            t.cu = dir == 0 ? across : along;
            t.cv = dir == 0 ? along : across;
            t.radius = rng_.Uniform(2.2, 3.4);
            t.crown_base_h = rng_.Uniform(2.5, 3.5);
            t.top_h = rng_.Uniform(8.0, 12.5);
            AddTree(t);
          }
        }
      }
    }
  }

 private:
  void AddTree(Tree t) {
    t.base_z = L_.TerrainAtCity(t.cu, t.cv);
    t.seed = static_cast<uint32_t>(rng_.Next());
    L_.trees.push_back(t);
  }

  // A building with axis a along s (along_s) or t, centred at (s, t) of the block.
  Building& AddBuilding(const BlockFrame& f, double s, double t, double len_s, double len_t, bool a_along_s) {
    Building b;
    f.ToCity(s, t, &b.cu, &b.cv);
    // Axis a along s means along u when s runs along u.
    const bool a_along_u = (a_along_s == f.s_along_u);
    b.a_along_v = !a_along_u;
    b.half_a = 0.5 * (a_along_s ? len_s : len_t);
    b.half_b = 0.5 * (a_along_s ? len_t : len_s);
    b.base_z = L_.TerrainAtCity(b.cu, b.cv);
    b.seed = static_cast<uint32_t>(rng_.Next());
    b.facade_material = static_cast<uint8_t>(rng_.UniformInt(0, 6));
    b.floor_h = rng_.Uniform(2.9, 3.4);
    b.window_pitch = rng_.Uniform(2.4, 3.6);
    L_.buildings.push_back(b);
    return L_.buildings.back();
  }

  void PitchedRoof(Building* b, double pitch_lo_deg, double pitch_hi_deg, double hipped_share) {
    b->roof = rng_.Bernoulli(hipped_share) ? RoofType::kHipped : RoofType::kGabled;
    b->pitch_tan = std::tan(rng_.Uniform(pitch_lo_deg, pitch_hi_deg) * kDeg);
    b->roof_material = static_cast<uint8_t>(rng_.UniformInt(0, 4));
    b->solar = rng_.Bernoulli(0.2);
  }

  void FlatRoof(Building* b, double parapet_share) {
    b->roof = RoofType::kFlat;
    b->roof_material = static_cast<uint8_t>(rng_.UniformInt(5, 8));
    if (rng_.Bernoulli(parapet_share)) b->parapet_h = rng_.Uniform(0.4, 0.9);
    b->solar = b->roof_material != 7 && rng_.Bernoulli(0.3);
  }

  // 0-n small boxes on a flat roof (stairwells, HVAC); added after the parent, so the parent is copied first.
  void RooftopBoxes(Building parent, int max_boxes) {
    const int n = rng_.UniformInt(0, max_boxes);
    for (int k = 0; k < n; ++k) {
      const double inset = 1.5 + parent.parapet_w;
      const double ha = rng_.Uniform(1.0, 2.5), hb = rng_.Uniform(1.0, 2.5);
      if (parent.half_a < ha + inset || parent.half_b < hb + inset) continue;
      const double a = rng_.Uniform(-(parent.half_a - ha - inset), parent.half_a - ha - inset);
      const double b = rng_.Uniform(-(parent.half_b - hb - inset), parent.half_b - hb - inset);
      Building box = parent;
      if (parent.a_along_v) {
        box.cu = parent.cu - b;
        box.cv = parent.cv + a;
      } else {
        box.cu = parent.cu + a;
        box.cv = parent.cv + b;
      }
      box.half_a = ha;
      box.half_b = hb;
      box.base_z = parent.base_z + parent.eaves_h;
      box.eaves_h = rng_.Uniform(1.5, 3.5);
      box.roof = RoofType::kFlat;
      box.parapet_h = 0.0;
      box.rooftop = true;
      box.solar = false;
      box.roof_material = 8;
      box.facade_material = 2;
      box.seed = static_cast<uint32_t>(rng_.Next());
      L_.buildings.push_back(box);
    }
  }

  void FillResidential(const BlockFrame& f) {
    const double row = 0.5 * f.lt;
    if (row < 12.0) return FillPark(f);
    for (int side = 0; side < 2; ++side) {
      double s = rng_.Uniform(0.0, 3.0);
      while (s + 12.0 < f.ls) {
        const double w = std::min(rng_.Uniform(14.0, 22.0), f.ls - s);
        const double len = rng_.Uniform(9.0, std::max(9.5, std::min(16.0, w - 3.0)));
        const double depth = rng_.Uniform(8.0, std::max(8.5, std::min(12.0, row - 7.0)));
        const double setback = rng_.Uniform(3.0, 5.5);
        const double t = side == 0 ? setback + 0.5 * depth : f.lt - setback - 0.5 * depth;
        const bool ridge_along_street = rng_.Bernoulli(0.7);
        Building& b = AddBuilding(f, s + 0.5 * w, t, len, depth, ridge_along_street);
        b.eaves_h = rng_.UniformInt(2, 3) * 2.8 + rng_.Uniform(0.2, 0.8);
        PitchedRoof(&b, 28.0, 45.0, 0.4);
        if (rng_.Bernoulli(0.6)) {
          Tree tree;
          const double tt = side == 0 ? setback + depth + rng_.Uniform(3.0, 5.0) : f.lt - setback - depth -
                                                                                      rng_.Uniform(3.0, 5.0);
          f.ToCity(s + rng_.Uniform(0.3, 0.7) * w, tt, &tree.cu, &tree.cv);
          tree.radius = rng_.Uniform(2.0, 3.5);
          tree.crown_base_h = rng_.Uniform(2.0, 3.0);
          tree.top_h = rng_.Uniform(6.0, 12.0);
          AddTree(tree);
        }
        s += w;
      }
    }
  }

  void UrbanSection(const BlockFrame& f, double s, double t, double len_s, double len_t, bool a_along_s) {
    Building& b = AddBuilding(f, s, t, len_s, len_t, a_along_s);
    const int floors = rng_.UniformInt(4, 8);
    b.eaves_h = floors * b.floor_h + 0.4;
    const double r = rng_.Uniform();
    if (r < 0.55) {
      FlatRoof(&b, 0.8);
      RooftopBoxes(b, 2);
    } else {
      PitchedRoof(&b, 28.0, 40.0, r < 0.7 ? 1.0 : 0.0);
    }
  }

  void FillUrban(const BlockFrame& f) {
    const double d = rng_.Uniform(11.0, 15.0);
    const bool courtyard = f.lt >= 2.0 * d + 6.0;
    const double depth = courtyard ? d : f.lt;
    const int rows = courtyard ? 2 : 1;
    for (int side = 0; side < rows; ++side) {
      const double t = side == 0 ? 0.5 * depth : f.lt - 0.5 * depth;
      for (double s = 0.0; s < f.ls - 1.0;) {
        double len = rng_.Uniform(14.0, 30.0);
        if (f.ls - s - len < 10.0) len = f.ls - s;
        UrbanSection(f, s + 0.5 * len, t, len, depth, true);
        s += len;
      }
    }
    if (!courtyard) return;
    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? 0.5 * d : f.ls - 0.5 * d;
      for (double t = d; t < f.lt - d - 1.0;) {
        double len = rng_.Uniform(14.0, 30.0);
        if (f.lt - d - t - len < 10.0) len = f.lt - d - t;
        UrbanSection(f, s, t + 0.5 * len, d, len, false);
        t += len;
      }
    }
    const double cs = f.ls - 2.0 * d - 6.0, ct = f.lt - 2.0 * d - 6.0;
    if (cs > 4.0 && ct > 4.0) {
      const int n = rng_.UniformInt(1, 3);
      for (int k = 0; k < n; ++k) {
        Tree tree;
        f.ToCity(d + 3.0 + rng_.Uniform(0.0, cs), d + 3.0 + rng_.Uniform(0.0, ct), &tree.cu, &tree.cv);
        tree.radius = rng_.Uniform(2.5, 4.5);
        tree.crown_base_h = rng_.Uniform(2.5, 4.0);
        tree.top_h = rng_.Uniform(8.0, 15.0);
        AddTree(tree);
      }
    }
  }

  void FillCommercial(const BlockFrame& f) {
    const double e = rng_.Uniform(4.0, 8.0);
    const double as = f.ls - 2.0 * e, at = f.lt - 2.0 * e;
    if (as < 20.0 || at < 20.0) return FillUrban(f);
    if (rng_.Bernoulli(0.45)) {
      // A podium with a tower on it (or beside it).
      const double ps = as * rng_.Uniform(0.6, 0.85), pt = at * rng_.Uniform(0.6, 0.85);
      const double s0 = e + rng_.Uniform(0.0, as - ps), t0 = e + rng_.Uniform(0.0, at - pt);
      Building& podium = AddBuilding(f, s0 + 0.5 * ps, t0 + 0.5 * pt, ps, pt, ps >= pt);
      podium.eaves_h = rng_.Uniform(6.0, 12.0);
      FlatRoof(&podium, 0.9);
      const double ts = std::min(ps, rng_.Uniform(18.0, 30.0)), tt = std::min(pt, rng_.Uniform(18.0, 30.0));
      Building& tower = AddBuilding(f, s0 + rng_.Uniform(0.5 * ts, ps - 0.5 * ts),
                                    t0 + rng_.Uniform(0.5 * tt, pt - 0.5 * tt), ts, tt, ts >= tt);
      tower.eaves_h = rng_.Uniform(25.0, 39.0);
      FlatRoof(&tower, 1.0);
      RooftopBoxes(tower, 3);
    } else {
      const int halls = rng_.UniformInt(1, 2);
      const double gap = halls == 2 ? rng_.Uniform(6.0, 12.0) : 0.0;
      const double each = (as - gap) / halls;
      for (int k = 0; k < halls; ++k) {
        const double len_t = at * rng_.Uniform(0.55, 0.9);
        const double t = e + rng_.Uniform(0.5 * len_t, at - 0.5 * len_t);
        Building& hall = AddBuilding(f, e + k * (each + gap) + 0.5 * each, t, each, len_t, each >= len_t);
        hall.eaves_h = rng_.Uniform(8.0, 22.0);
        FlatRoof(&hall, 0.7);
        RooftopBoxes(hall, 3);
      }
    }
    if (rng_.Bernoulli(0.6)) {
      for (double s = 3.0; s < f.ls - 3.0; s += 10.0) {
        for (const double t : {2.5, f.lt - 2.5}) {
          Tree tree;
          f.ToCity(s, t, &tree.cu, &tree.cv);
          tree.radius = rng_.Uniform(2.0, 3.0);
          tree.crown_base_h = 2.5;
          tree.top_h = rng_.Uniform(7.0, 10.0);
          AddTree(tree);
        }
      }
    }
  }

  void FillPark(const BlockFrame& f) {
    const double spacing = rng_.Uniform(9.0, 13.0);
    for (double s = 0.5 * spacing; s < f.ls; s += spacing) {
      for (double t = 0.5 * spacing; t < f.lt; t += spacing) {
        if (!rng_.Bernoulli(0.55)) continue;
        const double ss = s + rng_.Uniform(-0.3, 0.3) * spacing, tt = t + rng_.Uniform(-0.3, 0.3) * spacing;
        Tree tree;
        tree.radius = rng_.Uniform(2.5, 5.5);
        if (std::abs(tt - 0.5 * f.lt) < 2.0 + tree.radius) continue;  // the path along the park
        if (ss < tree.radius || tt < tree.radius || ss > f.ls - tree.radius || tt > f.lt - tree.radius) continue;
        f.ToCity(ss, tt, &tree.cu, &tree.cv);
        tree.crown_base_h = rng_.Uniform(2.0, 4.0);
        tree.top_h = rng_.Uniform(8.0, 18.0);
        AddTree(tree);
      }
    }
  }

  CityLayout& L_;
  Rng rng_;
};

}  // namespace

CityLayout GenerateCityLayout(const CityParams& p) {
  CityLayout layout;
  layout.cx = p.center_x;
  layout.cy = p.center_y;
  layout.cos_r = std::cos(p.rotation_deg * kDeg);
  layout.sin_r = std::sin(p.rotation_deg * kDeg);
  layout.half_extent = 0.5 * std::hypot(p.area_width_m, p.area_height_m) + p.margin_m;
  layout.seed = p.seed;

  Rng rng(StreamKey(p.seed, Stream::kLayout));
  Terrain& terrain = layout.terrain;
  terrain.ground_z = p.ground_z;
  const double slope = rng.Uniform(0.005, 0.02), slope_dir = rng.Uniform(0.0, 2.0 * M_PI);
  terrain.gx = slope * std::cos(slope_dir);
  terrain.gy = slope * std::sin(slope_dir);
  const double amplitudes[] = {1.5, 0.8, 0.35}, wavelengths[] = {420.0, 170.0, 80.0};
  for (int k = 0; k < 3; ++k) {
    const double dir = rng.Uniform(0.0, 2.0 * M_PI);
    const double wavenumber = 2.0 * M_PI / wavelengths[k];
    terrain.waves.push_back(
        {amplitudes[k], wavenumber * std::cos(dir), wavenumber * std::sin(dir), rng.Uniform(0.0, 2.0 * M_PI)});
  }

  Generator gen(&layout, rng.Next());
  layout.roads_u = gen.MakeBands();
  layout.roads_v = gen.MakeBands();
  const int nu = static_cast<int>(layout.roads_u.size()) + 1;
  const int nv = static_cast<int>(layout.roads_v.size()) + 1;
  layout.blocks.resize(static_cast<size_t>(nu) * nv);
  const double far = layout.half_extent + 120.0;
  for (int iv = 0; iv < nv; ++iv) {
    for (int iu = 0; iu < nu; ++iu) {
      const double u0 = iu == 0 ? -far : layout.roads_u[iu - 1].hi;
      const double u1 = iu == nu - 1 ? far : layout.roads_u[iu].lo;
      const double v0 = iv == 0 ? -far : layout.roads_v[iv - 1].hi;
      const double v1 = iv == nv - 1 ? far : layout.roads_v[iv].lo;
      const double r = rng.Uniform();
      BlockType type = r < 0.12 ? BlockType::kPark
                       : r < 0.47 ? BlockType::kResidential
                       : r < 0.82 ? BlockType::kUrban
                                  : BlockType::kCommercial;
      // The block(s) at the area centre are built up, so that even a tiny area shows buildings.
      const bool central = u0 < 15.0 && u1 > -15.0 && v0 < 15.0 && v1 > -15.0;
      if (central && type == BlockType::kPark) type = BlockType::kUrban;
      layout.blocks[static_cast<size_t>(iv) * nu + iu] = type;
      const double e = layout.half_extent;
      if (u1 < -e || u0 > e || v1 < -e || v0 > e) continue;
      BlockFrame f;
      f.u0 = u0;
      f.v0 = v0;
      f.s_along_u = (u1 - u0) >= (v1 - v0);
      f.ls = f.s_along_u ? u1 - u0 : v1 - v0;
      f.lt = f.s_along_u ? v1 - v0 : u1 - u0;
      gen.FillBlock(type, f);
    }
  }
  gen.StreetTrees();
  return layout;
}

}  // namespace sacfuse::sim
