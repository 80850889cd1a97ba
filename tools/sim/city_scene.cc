#include "tools/sim/city_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "tools/sim/city_texture.h"
#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {
constexpr double kNegInf = -std::numeric_limits<double>::infinity();
}  // namespace

CityScene::CityScene(CityLayout layout) : layout_(std::move(layout)) {
  texture_seed_ = StreamKey(layout_.seed, Stream::kTexture);
  origin_ = -layout_.half_extent - 150.0;
  n_ = static_cast<int>(std::ceil(2.0 * (layout_.half_extent + 150.0) / cell_));
  cells_.assign(static_cast<size_t>(n_) * n_, {});
  cell_top_.assign(cells_.size(), kNegInf);
  const uint32_t nb = static_cast<uint32_t>(layout_.buildings.size());
  auto insert = [&](uint32_t id, double u0, double v0, double u1, double v1, double top) {
    const int i0 = std::max(0, static_cast<int>(std::floor((u0 - origin_) / cell_)));
    const int i1 = std::min(n_ - 1, static_cast<int>(std::floor((u1 - origin_) / cell_)));
    const int j0 = std::max(0, static_cast<int>(std::floor((v0 - origin_) / cell_)));
    const int j1 = std::min(n_ - 1, static_cast<int>(std::floor((v1 - origin_) / cell_)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const size_t c = static_cast<size_t>(j) * n_ + i;
        cells_[c].push_back(id);
        cell_top_[c] = std::max(cell_top_[c], top);
      }
    }
  };
  double top = kNegInf;
  for (uint32_t k = 0; k < nb; ++k) {
    const Building& b = layout_.buildings[k];
    double u0, v0, u1, v1;
    b.BoundsUV(&u0, &v0, &u1, &v1);
    insert(k, u0, v0, u1, v1, b.Top());
    top = std::max(top, b.Top());
  }
  for (uint32_t k = 0; k < layout_.trees.size(); ++k) {
    const Tree& t = layout_.trees[k];
    insert(nb + k, t.cu - t.radius, t.cv - t.radius, t.cu + t.radius, t.cv + t.radius, t.Top());
    top = std::max(top, t.Top());
  }
  const double e = layout_.half_extent + 150.0;
  double lo, hi;
  layout_.terrain.Range(-e, -e, e, e, &lo, &hi);
  global_.lo = lo;
  global_.hi = std::max(hi, top);
}

int CityScene::CellIndex(double u, double v) const {
  const int i = static_cast<int>(std::floor((u - origin_) / cell_));
  const int j = static_cast<int>(std::floor((v - origin_) / cell_));
  if (i < 0 || j < 0 || i >= n_ || j >= n_) return -1;
  return j * n_ + i;
}

CityScene::Hit CityScene::QueryCity(double u, double v, double terrain_z) const {
  Hit hit;
  hit.z = terrain_z;
  const int c = CellIndex(u, v);
  if (c < 0 || cell_top_[c] <= terrain_z) return hit;
  const uint32_t nb = static_cast<uint32_t>(layout_.buildings.size());
  for (const uint32_t id : cells_[c]) {
    double z;
    if (id < nb) {
      z = layout_.buildings[id].HeightAt(u, v);
    } else {
      z = layout_.trees[id - nb].HeightAt(u, v, texture_seed_);
    }
    if (z > hit.z) {
      hit.z = z;
      hit.kind = id < nb ? Kind::kBuilding : Kind::kTree;
      hit.index = id < nb ? id : id - nb;
    }
  }
  return hit;
}

CityScene::Hit CityScene::Query(double x, double y) const {
  double u, v;
  layout_.WorldToCity(x, y, &u, &v);
  return QueryCity(u, v, layout_.terrain.Height(x - layout_.cx, y - layout_.cy));
}

double CityScene::Height(double x, double y) const { return Query(x, y).z; }

uint8_t CityScene::Class(double x, double y) const {
  switch (Query(x, y).kind) {
    case Kind::kBuilding:
      return kClassBuilding;
    case Kind::kTree:
      return kClassVegetation;
    case Kind::kTerrain:
      break;
  }
  return kClassGround;
}

Eigen::Vector3f CityScene::Albedo(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const {
  const bool wall = std::abs(n.z()) < 0.6f;
  double x = p.x(), y = p.y();
  if (wall) {
    // Step into the object behind the wall (n points out of it).
    const double nx = n.x(), ny = n.y();
    const double len = std::max(1e-6, std::hypot(nx, ny));
    x -= 0.25 * nx / len;
    y -= 0.25 * ny / len;
  }
  double u, v;
  layout_.WorldToCity(x, y, &u, &v);
  const Hit hit = QueryCity(u, v, layout_.terrain.Height(x - layout_.cx, y - layout_.cy));
  switch (hit.kind) {
    case Kind::kBuilding: {
      const Building& b = layout_.buildings[hit.index];
      double a, bb;
      b.ToLocal(u, v, &a, &bb);
      if (!wall) return RoofAlbedo(b, a, bb, texture_seed_);
      // Wall direction in the building frame: the normal mostly along a means the wall runs along b.
      const double nu = layout_.cos_r * n.x() + layout_.sin_r * n.y();
      const double nv = -layout_.sin_r * n.x() + layout_.cos_r * n.y();
      const double na = b.a_along_v ? nv : nu;
      const double nb = b.a_along_v ? -nu : nv;
      const double along = std::abs(na) > std::abs(nb) ? bb + b.half_b : a + b.half_a;
      return FacadeAlbedo(b, along, p.z() - b.base_z, texture_seed_);
    }
    case Kind::kTree:
      return TreeAlbedo(layout_.trees[hit.index], u, v, texture_seed_);
    case Kind::kTerrain:
      break;
  }
  return GroundAlbedo(layout_, u, v, texture_seed_);
}

HeightRange CityScene::RangeOver(const Box2d& box) const {
  // City-frame bounds of the box corners.
  double u0 = 1e300, v0 = 1e300, u1 = -1e300, v1 = -1e300;
  const double xs[] = {box.min.x(), box.max.x()}, ys[] = {box.min.y(), box.max.y()};
  for (const double x : xs) {
    for (const double y : ys) {
      double u, v;
      layout_.WorldToCity(x, y, &u, &v);
      u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
    }
  }
  HeightRange r;
  layout_.terrain.Range(box.min.x() - layout_.cx, box.min.y() - layout_.cy, box.max.x() - layout_.cx, box.max.y() - layout_.cy, &r.lo,
                        &r.hi);
  const int i0 = std::max(0, static_cast<int>(std::floor((u0 - origin_) / cell_)));
  const int i1 = std::min(n_ - 1, static_cast<int>(std::floor((u1 - origin_) / cell_)));
  const int j0 = std::max(0, static_cast<int>(std::floor((v0 - origin_) / cell_)));
  const int j1 = std::min(n_ - 1, static_cast<int>(std::floor((v1 - origin_) / cell_)));
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) r.hi = std::max(r.hi, cell_top_[static_cast<size_t>(j) * n_ + i]);
  }
  return r;
}

std::string CityScene::Describe() const {
  std::ostringstream os;
  os << "procedural city: " << layout_.buildings.size() << " buildings, " << layout_.trees.size() << " trees, "
     << layout_.roads_u.size() + layout_.roads_v.size() << " streets";
  return os.str();
}

}  // namespace sacfuse::sim
