#include "tiling/tile_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/option_check.h"

namespace sacfuse {

void ValidateTilingOptions(const TilingOptions& o) {
  OptionChecker check;
  check.AtLeast("TilingOptions.tile_size_m", o.tile_size_m, 0.0);
  check.AtLeast("TilingOptions.halo_m", o.halo_m, 0.0);
  check.AtLeast("TilingOptions.window_margin_px", o.window_margin_px, 0);
  check.Require(o.claim_timeout_s > 0, "TilingOptions.claim_timeout_s", OptionChecker::ToString(o.claim_timeout_s),
                "must be > 0");
  check.Require(o.z_max_m > o.z_min_m, "TilingOptions.z_max_m", OptionChecker::ToString(o.z_max_m),
                "must be > z_min_m (" + OptionChecker::ToString(o.z_min_m) + ")");
  check.ThrowIfFailed("tiling options");
}

namespace {

std::string Metres(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

// Refuses grids that are too fine before anything proportional to their tile count is allocated.
void CheckGridSize(const Box2d& area, double tile_size_m, double gsd_m) {
  const std::string key = "tiling.tile_size_m = " + Metres(tile_size_m) + ": ";
  const std::string area_text = Metres(area.max.x() - area.min.x()) + " x " + Metres(area.max.y() - area.min.y()) +
                                " m";
  if (gsd_m > 0 && tile_size_m < kMinTileSizeGsd * gsd_m) {
    throw ConfigError(key + "below " + Metres(kMinTileSizeGsd) + " ground sampling distances of the block (GSD " +
                      Metres(gsd_m) + " m, so at least " + Metres(kMinTileSizeGsd * gsd_m) +
                      " m); such tiles are mostly halo. Use a larger tile size, or 0 (automatic)");
  }
  const double nx = std::floor(area.max.x() / tile_size_m) - std::floor(area.min.x() / tile_size_m) + 1;
  const double ny = std::floor(area.max.y() / tile_size_m) - std::floor(area.min.y() / tile_size_m) + 1;
  if (!(nx * ny <= kMaxTiles)) {
    const double smallest = std::sqrt((area.max.x() - area.min.x()) * (area.max.y() - area.min.y()) / kMaxTiles);
    throw ConfigError(key + "the project area of " + area_text + " would be cut into " + Metres(nx) + " x " +
                      Metres(ny) + " = " + Metres(nx * ny) + " tiles, more than the limit of " + Metres(kMaxTiles) +
                      "; use tiles of at least ~" + Metres(std::ceil(smallest * 1.1)) + " m, or 0 (automatic)");
  }
}

}  // namespace

double BlockGsdAtHeight(const std::vector<View>& views, double z_m) {
  std::vector<double> gsd;
  for (const View& view : views) {
    const Eigen::Vector3d centre = view.CenterInWorld();
    const Eigen::Vector3d dir = view.ViewDirectionInWorld();
    const double focal = std::max(view.camera.fx, view.camera.fy);
    if (std::abs(dir.z()) < 1e-9 || !(focal > 0)) continue;
    const double t = (z_m - centre.z()) / dir.z();  // distance along the unit principal ray
    if (t > 0 && std::isfinite(t)) gsd.push_back(t / focal);
  }
  if (gsd.empty()) return 0.0;
  std::nth_element(gsd.begin(), gsd.begin() + gsd.size() / 2, gsd.end());
  return gsd[gsd.size() / 2];
}

TileGrid::TileGrid(const Box2d& area, double tile_size_m, double halo_m, double gsd_m)
    : area_(area), tile_size_m_(tile_size_m), halo_m_(halo_m), single_(tile_size_m == 0.0) {
  if (area.IsEmpty()) throw Error("tile grid: the project area is empty");
  if (!(tile_size_m >= 0.0) || !(halo_m >= 0.0) || !std::isfinite(tile_size_m) || !std::isfinite(halo_m)) {
    throw Error("tile grid: tile size and halo must be finite and >= 0");
  }
  if (single_) return;
  CheckGridSize(area, tile_size_m, gsd_m);
  kx0_ = static_cast<long long>(std::floor(area.min.x() / tile_size_m));
  ky0_ = static_cast<long long>(std::floor(area.min.y() / tile_size_m));
  // Fix rounding so that Edge(k0) <= min < Edge(k0 + 1) with the same formula CoreBounds uses.
  while (Edge(kx0_) > area.min.x()) --kx0_;
  while (Edge(kx0_ + 1) <= area.min.x()) ++kx0_;
  while (Edge(ky0_) > area.min.y()) --ky0_;
  while (Edge(ky0_ + 1) <= area.min.y()) ++ky0_;
  num_x_ = static_cast<int>(AxisIndex(area.max.x(), kx0_) + 1);
  num_y_ = static_cast<int>(AxisIndex(area.max.y(), ky0_) + 1);
}

long long TileGrid::AxisIndex(double v, long long k0) const {
  long long k = static_cast<long long>(std::floor(v / tile_size_m_));
  while (Edge(k) > v) --k;
  while (Edge(k + 1) <= v) ++k;
  return k - k0;
}

std::vector<TileIndex> TileGrid::Tiles() const {
  std::vector<TileIndex> out;
  out.reserve(size());
  for (int iy = 0; iy < num_y_; ++iy) {
    for (int ix = 0; ix < num_x_; ++ix) out.push_back({ix, iy});
  }
  return out;
}

std::string TileGrid::Id(const TileIndex& t) { return std::to_string(t.ix) + "_" + std::to_string(t.iy); }

std::optional<TileIndex> TileGrid::Parse(const std::string& id) const {
  int ix = 0, iy = 0;
  char extra = 0;
  if (std::sscanf(id.c_str(), "%d_%d%c", &ix, &iy, &extra) != 2) return std::nullopt;
  if (ix < 0 || iy < 0 || ix >= num_x_ || iy >= num_y_ || Id({ix, iy}) != id) return std::nullopt;
  return TileIndex{ix, iy};
}

Box2d TileGrid::CoreBounds(const TileIndex& t) const {
  if (single_) return area_;
  Box2d b;
  b.min = {Edge(kx0_ + t.ix), Edge(ky0_ + t.iy)};
  b.max = {Edge(kx0_ + t.ix + 1), Edge(ky0_ + t.iy + 1)};
  return b;
}

Box2d TileGrid::HaloBounds(const TileIndex& t) const {
  Box2d b = CoreBounds(t);
  b.min.array() -= halo_m_;
  b.max.array() += halo_m_;
  return b;
}

bool TileGrid::CoreContains(const TileIndex& t, double x, double y) const {
  if (single_) return true;
  const Box2d b = CoreBounds(t);
  return x >= b.min.x() && x < b.max.x() && y >= b.min.y() && y < b.max.y();
}

OwnedRegion TileGrid::OwnedRegionOf(const TileIndex& t) const {
  OwnedRegion region;
  if (single_) return region;
  const Box2d core = CoreBounds(t);
  if (t.ix > 0) region.min.x() = core.min.x();
  if (t.iy > 0) region.min.y() = core.min.y();
  if (t.ix + 1 < num_x_) region.max.x() = core.max.x();
  if (t.iy + 1 < num_y_) region.max.y() = core.max.y();
  return region;
}

TileIndex TileGrid::TileOf(double x, double y) const {
  if (single_) return {0, 0};
  const long long ix = std::clamp<long long>(AxisIndex(x, kx0_), 0, num_x_ - 1);
  const long long iy = std::clamp<long long>(AxisIndex(y, ky0_), 0, num_y_ - 1);
  return {static_cast<int>(ix), static_cast<int>(iy)};
}

}  // namespace sacfuse
