#include "tools/sim/las_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "io/las_reader.h"
#include "tools/sim/city_texture.h"
#include "tools/sim/noise.h"
#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {

constexpr float kNoZ = -std::numeric_limits<float>::infinity();

bool FormatHasRgb(int format) { return format == 2 || format == 3 || format == 5 || format == 7 || format == 8 || format == 10; }
bool IsVegetation(uint8_t c) { return c == 3 || c == 4 || c == 5; }

}  // namespace

LasScene::LasScene(const LasSceneOptions& o) : path_(o.path), seed_(StreamKey(o.seed, Stream::kTexture)) {
  LasReader reader(o.path);
  const LasHeader& header = reader.header();
  wkt_ = header.Wkt();
  has_rgb_ = FormatHasRgb(header.point_format);
  const Box2d file{header.min.x(), header.min.y(), header.max.x(), header.max.y()};
  if (!file.HasArea()) throw InputError(o.path, "the header bounds are empty; no area to simulate");
  area_ = file;
  const Eigen::Vector2d c = file.Center();
  if (o.area_width_m > 0.0 && o.area_width_m < file.Width()) {
    area_.min.x() = c.x() - 0.5 * o.area_width_m, area_.max.x() = c.x() + 0.5 * o.area_width_m;
  }
  if (o.area_height_m > 0.0 && o.area_height_m < file.Height()) {
    area_.min.y() = c.y() - 0.5 * o.area_height_m, area_.max.y() = c.y() + 0.5 * o.area_height_m;
  }
  extent_ = area_.Expanded(o.margin_m).Intersection(file);
  if (o.cell_m > 0.0) {
    cell_ = o.cell_m;
  } else {
    const double first = header.points_by_return[0] > 0 ? static_cast<double>(header.points_by_return[0])
                                                        : static_cast<double>(header.point_count);
    const double density = std::max(1e-3, first / (file.Width() * file.Height()));
    cell_ = std::clamp(std::round(std::sqrt(3.0 / density) / 0.05) * 0.05, 0.1, 2.0);
  }
  width_ = std::max(2, static_cast<int>(std::ceil(extent_.Width() / cell_)));
  height_ = std::max(2, static_cast<int>(std::ceil(extent_.Height() / cell_)));
  if (static_cast<double>(width_) * height_ > 4e8) {
    throw ConfigError("las_cell_m = " + std::to_string(cell_) + ": the DSM of " + o.path +
                      " would have more than 4e8 cells; use a larger cell or a smaller area");
  }
  extent_.max.x() = extent_.min.x() + width_ * cell_;
  extent_.max.y() = extent_.min.y() + height_ * cell_;
  z_base_ = header.min.z();
  const size_t n = static_cast<size_t>(width_) * height_;
  z_.assign(n, kNoZ);
  class_.assign(n, 0);
  std::vector<float> class_z(n, kNoZ);
  if (has_rgb_) rgb_.assign(n, {0, 0, 0});

  std::vector<LasPoint> chunk;
  while (reader.Read(&chunk, 1 << 16) > 0) {
    for (const LasPoint& p : chunk) {
      if (p.return_number > 1 || (p.flags & 0x4) != 0 || p.classification == 7 || p.classification == 18) continue;
      const int col = static_cast<int>(std::floor((p.xyz.x() - extent_.min.x()) / cell_));
      const int row = static_cast<int>(std::floor((p.xyz.y() - extent_.min.y()) / cell_));
      if (col < 0 || row < 0 || col >= width_ || row >= height_) continue;
      const size_t i = Index(row, col);
      const auto z = static_cast<float>(p.xyz.z() - z_base_);
      ++points_used_;
      if (z > z_[i]) {
        z_[i] = z;
        if (has_rgb_) {
          for (int k = 0; k < 3; ++k) rgb_[i][k] = static_cast<uint8_t>(p.rgb[k] >> 8);
        }
      }
      const uint8_t cls = p.classification;
      if (cls != 0 && cls != 1 && cls != 12 && z > class_z[i]) {
        class_z[i] = z;
        class_[i] = cls;
      }
    }
  }
  if (points_used_ == 0) {
    std::ostringstream os;
    os.precision(12);
    os << "no first-return points inside the simulated area [" << area_.min.x() << ", " << area_.max.x() << "] x ["
       << area_.min.y() << ", " << area_.max.y() << "]";
    throw InputError(o.path, os.str());
  }
  for (size_t i = 0; i < n; ++i) {
    if (class_[i] == 0 && z_[i] != kNoZ) class_[i] = 1;
  }
  FillHoles();

  std::vector<float> inside;
  for (int row = 0; row < height_; ++row) {
    for (int col = 0; col < width_; ++col) {
      const double x = extent_.min.x() + (col + 0.5) * cell_, y = extent_.min.y() + (row + 0.5) * cell_;
      if (area_.Contains(x, y)) inside.push_back(z_[Index(row, col)]);
    }
  }
  if (inside.empty()) inside = z_;
  const size_t k = inside.size() / 20;
  std::nth_element(inside.begin(), inside.begin() + k, inside.end());
  ground_z_ = z_base_ + inside[k];
  BuildBlockRanges();
}

void LasScene::FillHoles() {
  // Layer by layer from the filled cells inward (each layer computed from the previous state): O(cells).
  auto neighbours = [&](size_t i, auto&& fn) {
    const int row = static_cast<int>(i / width_), col = static_cast<int>(i % width_);
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int r = row + dr, c = col + dc;
        if ((dr != 0 || dc != 0) && r >= 0 && c >= 0 && r < height_ && c < width_) fn(Index(r, c));
      }
    }
  };
  std::vector<uint8_t> queued(z_.size(), 0);
  std::vector<size_t> frontier;
  for (size_t i = 0; i < z_.size(); ++i) {
    if (z_[i] != kNoZ) continue;
    bool next_to_data = false;
    neighbours(i, [&](size_t j) { next_to_data |= z_[j] != kNoZ; });
    if (next_to_data) {
      frontier.push_back(i);
      queued[i] = 1;
    }
  }
  std::vector<size_t> source(frontier.size());
  while (!frontier.empty()) {
    source.resize(frontier.size());
    for (size_t k = 0; k < frontier.size(); ++k) {
      std::pair<float, size_t> nb[8];
      int count = 0;
      neighbours(frontier[k], [&](size_t j) {
        if (z_[j] != kNoZ) nb[count++] = {z_[j], j};
      });
      for (int a = 1; a < count; ++a) {  // insertion sort of <= 8 values
        for (int b = a; b > 0 && nb[b] < nb[b - 1]; --b) std::swap(nb[b], nb[b - 1]);
      }
      source[k] = nb[(count - 1) / 2].second;  // lower median
    }
    std::vector<size_t> next;
    for (size_t k = 0; k < frontier.size(); ++k) {
      const size_t i = frontier[k], from = source[k];
      z_[i] = z_[from];
      class_[i] = class_[from];
      if (has_rgb_) rgb_[i] = rgb_[from];
    }
    for (const size_t i : frontier) {
      neighbours(i, [&](size_t j) {
        if (z_[j] == kNoZ && !queued[j]) {
          queued[j] = 1;
          next.push_back(j);
        }
      });
    }
    frontier.swap(next);
  }
}

void LasScene::BuildBlockRanges() {
  blocks_x_ = (width_ + kBlock - 1) / kBlock;
  blocks_y_ = (height_ + kBlock - 1) / kBlock;
  block_lo_.assign(static_cast<size_t>(blocks_x_) * blocks_y_, std::numeric_limits<float>::infinity());
  block_hi_.assign(block_lo_.size(), -std::numeric_limits<float>::infinity());
  for (int row = 0; row < height_; ++row) {
    for (int col = 0; col < width_; ++col) {
      const float z = z_[Index(row, col)];
      if (z == kNoZ) continue;
      // A cell influences bilinear values up to one cell away: count it in every block it touches.
      for (int br = std::max(0, (row - 1) / kBlock); br <= std::min(blocks_y_ - 1, (row + 1) / kBlock); ++br) {
        for (int bc = std::max(0, (col - 1) / kBlock); bc <= std::min(blocks_x_ - 1, (col + 1) / kBlock); ++bc) {
          const size_t b = static_cast<size_t>(br) * blocks_x_ + bc;
          block_lo_[b] = std::min(block_lo_[b], z);
          block_hi_[b] = std::max(block_hi_[b], z);
        }
      }
      global_.lo = std::min(global_.lo, z_base_ + z);
      global_.hi = std::max(global_.hi, z_base_ + z);
    }
  }
}

bool LasScene::Cell(double x, double y, int* row, int* col) const {
  if (!extent_.Contains(x, y)) return false;
  *col = std::clamp(static_cast<int>(std::floor((x - extent_.min.x()) / cell_)), 0, width_ - 1);
  *row = std::clamp(static_cast<int>(std::floor((y - extent_.min.y()) / cell_)), 0, height_ - 1);
  return true;
}

double LasScene::Height(double x, double y) const {
  if (!extent_.Contains(x, y)) return std::numeric_limits<double>::quiet_NaN();
  const double fx = (x - extent_.min.x()) / cell_ - 0.5, fy = (y - extent_.min.y()) / cell_ - 0.5;
  const int c0 = std::clamp(static_cast<int>(std::floor(fx)), 0, width_ - 1);
  const int r0 = std::clamp(static_cast<int>(std::floor(fy)), 0, height_ - 1);
  const int c1 = std::min(c0 + 1, width_ - 1), r1 = std::min(r0 + 1, height_ - 1);
  const double tx = std::clamp(fx - c0, 0.0, 1.0), ty = std::clamp(fy - r0, 0.0, 1.0);
  const double a = z_[Index(r0, c0)], b = z_[Index(r0, c1)], c = z_[Index(r1, c0)], d = z_[Index(r1, c1)];
  return z_base_ + (a + (b - a) * tx) * (1.0 - ty) + (c + (d - c) * tx) * ty;
}

uint8_t LasScene::Class(double x, double y) const {
  int row, col;
  return Cell(x, y, &row, &col) ? class_[Index(row, col)] : 0;
}

Eigen::Vector3f LasScene::Albedo(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const {
  const bool wall = std::abs(n.z()) < 0.6f;
  const double nxy = std::hypot(n.x(), n.y());
  double x = p.x(), y = p.y();
  if (wall && nxy > 0.0) x -= 0.3 * n.x() / nxy, y -= 0.3 * n.y() / nxy;
  int row, col;
  if (!Cell(x, y, &row, &col)) return Eigen::Vector3f(0.3f, 0.3f, 0.3f);
  const size_t i = Index(row, col);
  const uint8_t cls = class_[i];
  const double lx = p.x() - extent_.min.x(), ly = p.y() - extent_.min.y();
  // A pseudo-building per 25 m cell gives roof and façade colours that change between houses.
  Building b;
  b.seed = static_cast<uint32_t>(Hash3(seed_, static_cast<uint64_t>(std::floor(lx / 25.0)),
                                       static_cast<uint64_t>(std::floor(ly / 25.0))));
  b.facade_material = static_cast<uint8_t>(b.seed % 7);
  b.roof_material = static_cast<uint8_t>((b.seed >> 8) % 9);
  b.base_z = ground_z_;
  b.floor_h = 3.1;
  b.window_pitch = 2.9;
  if (wall) {
    if (IsVegetation(cls)) {
      Tree t;
      t.seed = b.seed;
      t.radius = 1e3;
      return TreeAlbedo(t, lx, ly, seed_);
    }
    b.eaves_h = Height(x, y) - ground_z_;
    const double along = lx * (-n.y() / nxy) + ly * (n.x() / nxy);
    return FacadeAlbedo(b, along + 1000.0, p.z() - ground_z_, seed_);
  }
  if (has_rgb_) {
    const auto& c = rgb_[i];
    const float fine = static_cast<float>(1.0 + 0.04 * (CellHash(seed_, std::floor(lx / 0.3), std::floor(ly / 0.3)) - 0.5));
    return (Eigen::Vector3f(c[0], c[1], c[2]) / 255.0f * fine).cwiseMin(1.0f);
  }
  if (cls == kClassBuilding) {
    // Roof colours blend smoothly between a terracotta and a grey family (no fake edges inside a roof), with
    // weathering and a fine speckle; the shading of the measured surface adds the rest.
    const double t = 0.5 + 0.5 * Fbm(seed_ + 14, lx, ly, 35.0, 2);
    const Eigen::Vector3f red(0.55f, 0.27f, 0.19f), grey(0.42f, 0.42f, 0.44f);
    const float weather = static_cast<float>(1.0 + 0.12 * Fbm(seed_ + 15, lx, ly, 3.0, 3) +
                                             0.06 * (CellHash(seed_ + 16, std::floor(lx / 0.25), std::floor(ly / 0.25)) - 0.5));
    return ((red * static_cast<float>(t) + grey * static_cast<float>(1.0 - t)) * weather).cwiseMin(1.0f);
  }
  if (IsVegetation(cls)) {
    Tree t;
    t.seed = b.seed;
    t.radius = 1e3;
    return TreeAlbedo(t, lx, ly, seed_);
  }
  if (cls == 9) return Eigen::Vector3f(0.08f, 0.12f, 0.16f) * static_cast<float>(1.0 + 0.1 * Fbm(seed_, lx, ly, 5.0, 3));
  // Ground and everything else: asphalt and grass patches.
  const double patch = Fbm(seed_ + 11, lx, ly, 25.0, 3);
  const double fine = 0.05 * (CellHash(seed_, std::floor(lx / 0.2), std::floor(ly / 0.2)) - 0.5);
  if (patch > 0.0) {
    const float g = static_cast<float>(0.26 + 0.04 * Fbm(seed_ + 12, lx, ly, 6.0, 3) + fine);
    return Eigen::Vector3f(g, g, g * 1.03f);
  }
  return Eigen::Vector3f(0.28f, 0.42f, 0.16f) * static_cast<float>(0.85 + 0.3 * Fbm(seed_ + 13, lx, ly, 4.0, 4));
}

HeightRange LasScene::RangeOver(const Box2d& box) const {
  HeightRange r;
  if (!box.Intersects(extent_)) return r;
  const int c0 = std::clamp(static_cast<int>(std::floor((box.min.x() - extent_.min.x()) / cell_)) - 1, 0, width_ - 1);
  const int c1 = std::clamp(static_cast<int>(std::floor((box.max.x() - extent_.min.x()) / cell_)) + 1, 0, width_ - 1);
  const int r0 = std::clamp(static_cast<int>(std::floor((box.min.y() - extent_.min.y()) / cell_)) - 1, 0, height_ - 1);
  const int r1 = std::clamp(static_cast<int>(std::floor((box.max.y() - extent_.min.y()) / cell_)) + 1, 0, height_ - 1);
  for (int br = r0 / kBlock; br <= r1 / kBlock; ++br) {
    for (int bc = c0 / kBlock; bc <= c1 / kBlock; ++bc) {
      const size_t b = static_cast<size_t>(br) * blocks_x_ + bc;
      r.lo = std::min(r.lo, z_base_ + block_lo_[b]);
      r.hi = std::max(r.hi, z_base_ + block_hi_[b]);
    }
  }
  return r;
}

std::string LasScene::Describe() const {
  std::ostringstream os;
  os << "LiDAR DSM from " << path_ << ": " << width_ << " x " << height_ << " cells of " << cell_ << " m, "
     << points_used_ << " first returns" << (has_rgb_ ? ", RGB" : ", procedural colours");
  return os.str();
}

}  // namespace sacfuse::sim
