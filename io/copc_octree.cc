#include "io/copc_octree.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include <tbb/parallel_for.h>

#include "io/las_format.h"

namespace sacfuse::copc {
namespace lf = las_format;
namespace {

constexpr size_t kParallelPoints = 50000;  // children of a node with more points are built in parallel

int64_t FloorEven(int64_t v) { return v - (((v % 2) + 2) % 2); }

}  // namespace

Cube Cube::Around(const std::array<int32_t, 3>& lo, const std::array<int32_t, 3>& hi) {
  std::array<int64_t, 3> centre{};
  int64_t half = 16;  // the smallest cube: 32 half-quanta
  for (int a = 0; a < 3; ++a) {
    const int64_t pmin = 2 * int64_t{lo[a]} + 1, pmax = 2 * int64_t{hi[a]} + 1;
    centre[a] = FloorEven(int64_t{lo[a]} + hi[a] + 1);  // (pmin + pmax) / 2, rounded down to even
    half = std::max({half, centre[a] - pmin, pmax - centre[a] + 1});
  }
  const uint64_t needed = 2 * static_cast<uint64_t>(half);
  Cube cube;
  cube.k_ = 2;
  while ((uint64_t{16} << cube.k_) < needed) ++cube.k_;
  cube.c_ = (needed + (uint64_t{1} << cube.k_) - 1) >> cube.k_;  // ceil: 8..16
  if (cube.c_ < 8) cube.c_ = 8;
  if (cube.c_ == 16) {
    cube.c_ = 8;
    ++cube.k_;
  }
  const int64_t half_side = static_cast<int64_t>(cube.c_ << (cube.k_ - 1));  // even: k >= 2
  for (int a = 0; a < 3; ++a) cube.min_[a] = centre[a] - half_side;
  return cube;
}

uint64_t Cube::Coordinate(int axis, int32_t stored, int level) const {
  const uint64_t d = static_cast<uint64_t>(2 * int64_t{stored} + 1 - min_[axis]);  // in [1, side)
  // floor(d 2^level / (c 2^k)) = floor(floor(d 2^level / 2^k) / c)
  const uint64_t scaled = level >= k_ ? d << (level - k_) : d >> (k_ - level);
  return scaled / c_;
}

VoxelKey Cube::KeyOf(const int32_t stored[3], int level) const {
  return {level, static_cast<int32_t>(Coordinate(0, stored[0], level)),
          static_cast<int32_t>(Coordinate(1, stored[1], level)), static_cast<int32_t>(Coordinate(2, stored[2], level))};
}

uint32_t Cube::CellOf(const int32_t stored[3], const VoxelKey& node, double* distance2) const {
  const int level = node.level + kCellBits;
  const int32_t origin[3] = {node.x, node.y, node.z};
  // Cell size in half-quanta: c 2^k / 2^level (exact in a double).
  const double cell = std::ldexp(static_cast<double>(c_), k_ - level);
  uint32_t id = 0;
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const uint64_t q = Coordinate(a, stored[a], level);
    const uint64_t local = q - (static_cast<uint64_t>(origin[a]) << kCellBits);  // 0 .. kCells - 1
    id |= static_cast<uint32_t>(local) << (kCellBits * a);
    const double d = static_cast<double>(2 * int64_t{stored[a]} + 1 - min_[a]);
    const double off = d - (static_cast<double>(q) + 0.5) * cell;
    d2 += off * off;
  }
  *distance2 = d2;
  return id;
}

int Cube::OctantOf(const int32_t stored[3], const VoxelKey& node) const {
  int octant = 0;
  for (int a = 0; a < 3; ++a) {
    if (Coordinate(a, stored[a], node.level + 1) & 1) octant |= 1 << a;
  }
  return octant;
}

Info Cube::ToInfo(double scale, const Eigen::Vector3d& offset) const {
  Info info;
  const int64_t half_side = static_cast<int64_t>(c_ << (k_ - 1));
  for (int a = 0; a < 3; ++a) {
    // Half-quantum position p is stored integer (p - 1) / 2.
    info.center[a] = offset[a] + scale * static_cast<double>(min_[a] + half_side - 1) / 2.0;
  }
  info.halfsize = scale * static_cast<double>(half_side) / 2.0;
  info.spacing = 2.0 * info.halfsize / kCells;
  return info;
}

void RecordView::Stored(uint32_t i, int32_t out[3]) const {
  const uint8_t* r = data + static_cast<size_t>(i) * record_length;
  out[0] = lf::GetI32(r);
  out[1] = lf::GetI32(r + 4);
  out[2] = lf::GetI32(r + 8);
}

void SelectOnePerCell(const Cube& cube, const VoxelKey& node, const RecordView& records,
                      const std::vector<uint32_t>& points, std::vector<uint32_t>* own, std::vector<uint32_t>* rest) {
  // Open addressing on the cell id; at most kCells^3 = 2^21 cells are occupied, so 2^22 slots keep the load <= 1/2.
  struct Slot {
    uint32_t cell_plus_1 = 0;
    uint32_t best = 0;  // position in `points`
    double distance2 = 0.0;
  };
  size_t capacity = 16;
  while (capacity < 2 * points.size() && capacity < (size_t{1} << 22)) capacity *= 2;
  std::vector<Slot> slots(capacity);
  const size_t mask = capacity - 1;
  int32_t stored[3];
  for (size_t pos = 0; pos < points.size(); ++pos) {
    records.Stored(points[pos], stored);
    double d2 = 0.0;
    const uint32_t cell = cube.CellOf(stored, node, &d2);
    size_t h = (static_cast<size_t>(cell) * 2654435761u) & mask;
    while (true) {
      Slot& s = slots[h];
      if (s.cell_plus_1 == 0) {
        s = {cell + 1, static_cast<uint32_t>(pos), d2};
        break;
      }
      if (s.cell_plus_1 == cell + 1) {
        if (d2 < s.distance2) {
          s.best = static_cast<uint32_t>(pos);
          s.distance2 = d2;
        }
        break;
      }
      h = (h + 1) & mask;
    }
  }
  std::vector<uint8_t> chosen(points.size(), 0);
  for (const Slot& s : slots) {
    if (s.cell_plus_1 != 0) chosen[s.best] = 1;
  }
  own->clear();
  rest->clear();
  for (size_t pos = 0; pos < points.size(); ++pos) (chosen[pos] ? own : rest)->push_back(points[pos]);
}

BuiltSubtree BuildSubtree(const Cube& cube, const VoxelKey& node, const RecordView& records,
                          std::vector<uint32_t> points, size_t max_points) {
  BuiltSubtree out;
  if (points.size() <= max_points || node.level >= cube.max_node_level()) {
    out.own = std::move(points);
    return out;
  }
  std::vector<uint32_t> rest;
  SelectOnePerCell(cube, node, records, points, &out.own, &rest);
  points = std::vector<uint32_t>();
  std::array<std::vector<uint32_t>, 8> children;
  int32_t stored[3];
  for (uint32_t i : rest) {
    records.Stored(i, stored);
    children[cube.OctantOf(stored, node)].push_back(i);
  }
  const bool parallel = rest.size() > kParallelPoints;
  rest = std::vector<uint32_t>();
  std::array<BuiltSubtree, 8> built;
  const auto build = [&](size_t o) {
    if (!children[o].empty()) {
      built[o] = BuildSubtree(cube, node.Child(static_cast<int>(o)), records, std::move(children[o]), max_points);
    }
  };
  if (parallel) {
    tbb::parallel_for(size_t{0}, size_t{8}, build);
  } else {
    for (size_t o = 0; o < 8; ++o) build(o);
  }
  for (int o = 0; o < 8; ++o) {
    if (built[o].own.empty() && built[o].descendants.empty()) continue;
    for (BuiltNode& n : built[o].descendants) out.descendants.push_back(std::move(n));
    out.descendants.push_back({node.Child(o), std::move(built[o].own)});
  }
  return out;
}

}  // namespace sacfuse::copc
