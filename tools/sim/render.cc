#include "tools/sim/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/backproject.h"
#include "core/error.h"

namespace sacfuse::sim {
namespace {

constexpr uint64_t kEmpty = std::numeric_limits<uint64_t>::max();

// Octahedral encoding of a unit vector in 2 x 16 bits.
uint32_t EncodeNormal(const Eigen::Vector3d& n) {
  const double l1 = std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z());
  double px = n.x() / l1, py = n.y() / l1;
  if (n.z() < 0.0) {
    const double qx = (1.0 - std::abs(py)) * (px >= 0.0 ? 1.0 : -1.0);
    const double qy = (1.0 - std::abs(px)) * (py >= 0.0 ? 1.0 : -1.0);
    px = qx, py = qy;
  }
  const auto ex = static_cast<uint32_t>(std::lround((px * 0.5 + 0.5) * 65535.0));
  const auto ey = static_cast<uint32_t>(std::lround((py * 0.5 + 0.5) * 65535.0));
  return (ex << 16) | ey;
}

Eigen::Vector3f DecodeNormal(uint32_t code) {
  const float px = static_cast<float>(code >> 16) / 65535.0f * 2.0f - 1.0f;
  const float py = static_cast<float>(code & 0xffffu) / 65535.0f * 2.0f - 1.0f;
  Eigen::Vector3f n(px, py, 1.0f - std::abs(px) - std::abs(py));
  if (n.z() < 0.0f) {
    const float qx = (1.0f - std::abs(py)) * (px >= 0.0f ? 1.0f : -1.0f);
    const float qy = (1.0f - std::abs(px)) * (py >= 0.0f ? 1.0f : -1.0f);
    n.x() = qx, n.y() = qy;
  }
  return n.normalized();
}

uint64_t PackKey(float depth, uint32_t normal_code) {
  uint32_t bits;
  std::memcpy(&bits, &depth, sizeof(bits));
  return (static_cast<uint64_t>(bits) << 32) | normal_code;
}

float KeyDepth(uint64_t key) {
  const auto bits = static_cast<uint32_t>(key >> 32);
  float depth;
  std::memcpy(&depth, &bits, sizeof(depth));
  return depth;
}

void AtomicMin(uint64_t* slot, uint64_t value) {
  uint64_t current = __atomic_load_n(slot, __ATOMIC_RELAXED);
  while (value < current &&
         !__atomic_compare_exchange_n(slot, &current, value, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
  }
}

struct ZTarget {
  int width = 0, height = 0;
  double scale_x = 1.0, scale_y = 1.0;  // image pixels -> target pixels
  std::vector<uint64_t> keys;
};

struct Vertex {
  double u = 0.0, v = 0.0, inv_z = 0.0;  // image coordinates, 1 / camera z
  Eigen::Vector3d rel;                   // world point minus camera centre
  bool valid = false;
};

// Rasterises one triangle into `target`; `code` is computed lazily (the facet normal) when a pixel is covered.
template <typename CodeFn>
size_t RasterTriangle(const Vertex& a, const Vertex& b, const Vertex& c, ZTarget* target, CodeFn&& code_fn) {
  const double au = a.u * target->scale_x, av = a.v * target->scale_y;
  const double bu = b.u * target->scale_x, bv = b.v * target->scale_y;
  const double cu = c.u * target->scale_x, cv = c.v * target->scale_y;
  const int c0 = std::max(0, static_cast<int>(std::ceil(std::min({au, bu, cu}) - 0.5)));
  const int c1 = std::min(target->width - 1, static_cast<int>(std::floor(std::max({au, bu, cu}) - 0.5)));
  if (c0 > c1) return 0;
  const int r0 = std::max(0, static_cast<int>(std::ceil(std::min({av, bv, cv}) - 0.5)));
  const int r1 = std::min(target->height - 1, static_cast<int>(std::floor(std::max({av, bv, cv}) - 0.5)));
  if (r0 > r1) return 0;
  const double area = (bu - au) * (cv - av) - (bv - av) * (cu - au);
  if (std::abs(area) < 1e-14) return 0;
  const double inv_area = 1.0 / area;
  constexpr double kEps = -1e-9;
  size_t covered = 0;
  uint32_t code = 0;
  bool have_code = false;
  for (int row = r0; row <= r1; ++row) {
    const double pv = row + 0.5;
    for (int col = c0; col <= c1; ++col) {
      const double pu = col + 0.5;
      const double w0 = ((bu - pu) * (cv - pv) - (bv - pv) * (cu - pu)) * inv_area;
      const double w1 = ((cu - pu) * (av - pv) - (cv - pv) * (au - pu)) * inv_area;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < kEps || w1 < kEps || w2 < kEps) continue;
      const double inv_z = w0 * a.inv_z + w1 * b.inv_z + w2 * c.inv_z;
      if (!(inv_z > 0.0)) continue;
      if (!have_code) {
        code = code_fn();
        have_code = true;
      }
      AtomicMin(&target->keys[static_cast<size_t>(row) * target->width + col],
                PackKey(static_cast<float>(1.0 / inv_z), code));
      ++covered;
    }
  }
  return covered;
}

struct Tile {
  Box2d box;
  double spacing;
};

}  // namespace

double NearestPowerOfTwo(double x) { return std::exp2(std::round(std::log2(x))); }

RenderedView RenderView(const RenderRequest& req) {
  if (req.surface == nullptr || !req.camera.IsValid()) throw Error("RenderView: no surface or an invalid camera");
  const Surface& surface = *req.surface;
  const PinholeCamera& cam = req.camera;
  const Rigid3d world_from_cam = req.cam_from_world.Inverse();
  const Eigen::Matrix3d r_wc = world_from_cam.rotation.toRotationMatrix();
  const Eigen::Matrix3d r_cw = r_wc.transpose();
  const Eigen::Vector3d center = world_from_cam.translation;
  const double focal = std::min(cam.fx, cam.fy);
  const int depth_w = req.depth_width > 0 ? req.depth_width : cam.width;
  const int depth_h = req.depth_height > 0 ? req.depth_height : cam.height;
  const bool separate_depth = depth_w != cam.width || depth_h != cam.height;

  RenderedView out;
  ZTarget image_z;
  image_z.width = cam.width;
  image_z.height = cam.height;
  image_z.keys.assign(static_cast<size_t>(cam.width) * cam.height, kEmpty);
  ZTarget depth_z;
  if (separate_depth) {
    depth_z.width = depth_w;
    depth_z.height = depth_h;
    depth_z.scale_x = static_cast<double>(depth_w) / cam.width;
    depth_z.scale_y = static_cast<double>(depth_h) / cam.height;
    depth_z.keys.assign(static_cast<size_t>(depth_w) * depth_h, kEmpty);
  }

  // Footprint region: rays through the image border meet the lowest and highest planes of the scene.
  const HeightRange global = surface.GlobalRange();
  std::vector<Tile> tiles;
  if (!global.IsEmpty() && center.z() > global.hi) {
    Box2d region{1e300, 1e300, -1e300, -1e300};
    const double max_reach = 20.0 * (center.z() - global.lo);
    for (int k = 0; k < 16; ++k) {
      const double t = (k % 4) / 4.0;
      const double u = k < 4 ? t * cam.width : k < 8 ? cam.width : k < 12 ? (1.0 - t) * cam.width : 0.0;
      const double v = k < 4 ? 0.0 : k < 8 ? t * cam.height : k < 12 ? cam.height : (1.0 - t) * cam.height;
      const Eigen::Vector3d d = r_wc * cam.Unproject(u, v, 1.0);
      for (const double plane : {global.lo, global.hi}) {
        Eigen::Vector2d p;
        if (d.z() < -1e-6) {
          const double s = (plane - center.z()) / d.z();
          p = (center + s * d).head<2>();
        } else {
          p = center.head<2>();
        }
        const Eigen::Vector2d off = p - center.head<2>();
        if (d.z() >= -1e-6 || off.norm() > max_reach) {
          const Eigen::Vector2d dir = d.head<2>().norm() > 0 ? Eigen::Vector2d(d.head<2>().normalized())
                                                             : Eigen::Vector2d(0.0, 0.0);
          p = center.head<2>() + max_reach * dir;
        }
        region.min.x() = std::min(region.min.x(), p.x()), region.max.x() = std::max(region.max.x(), p.x());
        region.min.y() = std::min(region.min.y(), p.y()), region.max.y() = std::max(region.max.y(), p.y());
      }
    }
    region = region.Intersection(surface.Extent());
    const double finest = NearestPowerOfTwo(req.sampling * (center.z() - global.hi) / focal);
    const double tile_size = std::max(1.0, 64.0 * finest);
    if (region.HasArea()) {
      const auto i0 = static_cast<int64_t>(std::floor(region.min.x() / tile_size));
      const auto i1 = static_cast<int64_t>(std::floor(region.max.x() / tile_size));
      const auto j0 = static_cast<int64_t>(std::floor(region.min.y() / tile_size));
      const auto j1 = static_cast<int64_t>(std::floor(region.max.y() / tile_size));
      for (int64_t j = j0; j <= j1; ++j) {
        for (int64_t i = i0; i <= i1; ++i) {
          Tile tile;
          tile.box = {i * tile_size, j * tile_size, (i + 1) * tile_size, (j + 1) * tile_size};
          const HeightRange range = surface.RangeOver(tile.box);
          if (range.IsEmpty()) continue;
          // Cull tiles whose box projects outside the image.
          double u0 = 1e300, v0 = 1e300, u1 = -1e300, v1 = -1e300;
          bool behind = false;
          for (int k = 0; k < 8; ++k) {
            const Eigen::Vector3d corner((k & 1) ? tile.box.max.x() : tile.box.min.x(), (k & 2) ? tile.box.max.y() : tile.box.min.y(),
                                         (k & 4) ? range.hi : range.lo);
            const Eigen::Vector3d pc = r_cw * (corner - center);
            if (pc.z() <= 1e-3) {
              behind = true;
              break;
            }
            const Eigen::Vector2d uv = cam.Project(pc);
            u0 = std::min(u0, uv.x()), u1 = std::max(u1, uv.x()), v0 = std::min(v0, uv.y()), v1 = std::max(v1, uv.y());
          }
          if (behind) continue;
          if (u1 < -2.0 || v1 < -2.0 || u0 > cam.width + 2.0 || v0 > cam.height + 2.0) continue;
          // Nearest point of the tile's 3D box to the camera sets the local GSD.
          const Eigen::Vector3d nearest(std::clamp(center.x(), tile.box.min.x(), tile.box.max.x()),
                                        std::clamp(center.y(), tile.box.min.y(), tile.box.max.y()),
                                        std::clamp(center.z(), range.lo, range.hi));
          tile.spacing = std::min(tile_size, NearestPowerOfTwo(req.sampling * (nearest - center).norm() / focal));
          tiles.push_back(tile);
        }
      }
    }
  }

  std::atomic<size_t> triangles{0};
  tbb::parallel_for(size_t{0}, size_t{tiles.size()}, [&](size_t t) {
    const Tile& tile = tiles[t];
    const double s = tile.spacing;
    const auto ix0 = static_cast<int64_t>(std::floor(tile.box.min.x() / s)) - 1;
    const auto ix1 = static_cast<int64_t>(std::ceil(tile.box.max.x() / s)) + 1;
    const auto iy0 = static_cast<int64_t>(std::floor(tile.box.min.y() / s)) - 1;
    const auto iy1 = static_cast<int64_t>(std::ceil(tile.box.max.y() / s)) + 1;
    const int nx = static_cast<int>(ix1 - ix0 + 1), ny = static_cast<int>(iy1 - iy0 + 1);
    std::vector<Vertex> verts(static_cast<size_t>(nx) * ny);
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const double x = (ix0 + i) * s, y = (iy0 + j) * s;
        const double z = surface.Height(x, y);
        Vertex& vert = verts[static_cast<size_t>(j) * nx + i];
        if (!std::isfinite(z)) continue;
        vert.rel = Eigen::Vector3d(x, y, z) - center;
        const Eigen::Vector3d pc = r_cw * vert.rel;
        if (pc.z() <= 1e-3) continue;
        vert.inv_z = 1.0 / pc.z();
        vert.u = cam.fx * pc.x() * vert.inv_z + cam.cx;
        vert.v = cam.fy * pc.y() * vert.inv_z + cam.cy;
        vert.valid = true;
      }
    }
    size_t count = 0;
    for (int j = 0; j + 1 < ny; ++j) {
      for (int i = 0; i + 1 < nx; ++i) {
        const Vertex& v00 = verts[static_cast<size_t>(j) * nx + i];
        const Vertex& v10 = verts[static_cast<size_t>(j) * nx + i + 1];
        const Vertex& v01 = verts[static_cast<size_t>(j + 1) * nx + i];
        const Vertex& v11 = verts[static_cast<size_t>(j + 1) * nx + i + 1];
        const Vertex* tris[2][3] = {{&v00, &v10, &v11}, {&v00, &v11, &v01}};
        for (const auto& tri : tris) {
          if (!tri[0]->valid || !tri[1]->valid || !tri[2]->valid) continue;
          auto code_fn = [&] {
            Eigen::Vector3d n = (tri[1]->rel - tri[0]->rel).cross(tri[2]->rel - tri[0]->rel);
            if (n.dot(-tri[0]->rel) < 0.0) n = -n;  // toward the camera
            const double len = n.norm();
            return EncodeNormal(len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d(0, 0, 1));
          };
          RasterTriangle(*tri[0], *tri[1], *tri[2], &image_z, code_fn);
          if (separate_depth) RasterTriangle(*tri[0], *tri[1], *tri[2], &depth_z, code_fn);
          ++count;
        }
      }
    }
    triangles += count;
  });
  out.tiles = tiles.size();
  out.triangles = triangles.load();

  const ZTarget& dz = separate_depth ? depth_z : image_z;
  out.depth = DepthMap(depth_w, depth_h, 1, 0.0f);
  tbb::parallel_for(0, depth_h, [&](int row) {
    for (int col = 0; col < depth_w; ++col) {
      const uint64_t key = dz.keys[static_cast<size_t>(row) * depth_w + col];
      out.depth.at(row, col) = key == kEmpty ? 0.0f : KeyDepth(key);
    }
  });
  if (separate_depth) std::vector<uint64_t>().swap(depth_z.keys);
  if (!req.render_image) return out;

  out.image = RgbImage(cam.width, cam.height, 3, 0);
  tbb::parallel_for(0, cam.height, [&](int row) {
    for (int col = 0; col < cam.width; ++col) {
      const uint64_t key = image_z.keys[static_cast<size_t>(row) * cam.width + col];
      if (key == kEmpty) continue;
      const float depth = KeyDepth(key);
      const Eigen::Vector3f n = DecodeNormal(static_cast<uint32_t>(key & 0xffffffffu));
      const Eigen::Vector3d p = center + r_wc * DepthPixelInCamera(cam, col, row, depth);
      const Eigen::Vector3f rgb = surface.Albedo(p, n) * req.lighting.Shade(n) * 255.0f;
      for (int c = 0; c < 3; ++c) {
        out.image.at(row, col, c) = static_cast<uint8_t>(std::clamp(std::lround(rgb[c]), 0L, 255L));
      }
    }
  });
  return out;
}

}  // namespace sacfuse::sim
