#include "io/copc_octree.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>

#include <tbb/enumerable_thread_specific.h>
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

namespace {

// A node's 128^3 cells are chosen in 8^3 groups of 16^3 cells each: a group's points are chosen from alone, in a
// table of its 4,096 cells, so the groups run in parallel and every point's choice is the one a serial pass makes.
constexpr int kGroupBits = 3;
constexpr int kCellInGroupBits = kCellBits - kGroupBits;
constexpr int kGroups = 1 << (3 * kGroupBits);
constexpr int kGroupCells = 1 << (3 * kCellInGroupBits);
constexpr size_t kBlockPoints = size_t{1} << 15;  // points per task of the passes over all points

int Axis(uint32_t cell, int axis) { return static_cast<int>((cell >> (kCellBits * axis)) & (kCells - 1)); }

int CellInGroup(uint32_t cell) {
  int c = 0;
  for (int a = 0; a < 3; ++a) c |= (Axis(cell, a) & ((1 << kCellInGroupBits) - 1)) << (kCellInGroupBits * a);
  return c;
}

// The child octant (1 = x, 2 = y, 4 = z) holding a group: the top bit of its position on each axis.
int OctantOfGroup(int group) {
  int octant = 0;
  for (int a = 0; a < 3; ++a) octant |= ((group >> (kGroupBits * a + kGroupBits - 1)) & 1) << a;
  return octant;
}

size_t Blocks(size_t n) { return (n + kBlockPoints - 1) / kBlockPoints; }

// f(pos) for every pos < n, blocks of positions in parallel.
template <typename F>
void ForEachPosition(size_t n, const F& f) {
  tbb::parallel_for(size_t{0}, Blocks(n), [&](size_t b) {
    for (size_t pos = b * kBlockPoints; pos < std::min(n, (b + 1) * kBlockPoints); ++pos) f(pos);
  });
}

// The nearest point found so far in each cell of a group (reused by the tasks of a thread; emptied after a group).
struct Best {
  uint32_t pos_plus_1 = 0;
  double distance2 = 0.0;
};
struct GroupTable {
  std::vector<Best> best = std::vector<Best>(kGroupCells);
  std::vector<int> filled;
};

// Positions 0 .. bins.size() - 1 grouped by their bin (< num_bins), stably: bin b's positions are
// order[start[b] .. start[b + 1]), increasing. Counted and scattered per block of positions in parallel.
void GroupByBin(const std::vector<uint16_t>& bins, int num_bins, std::unique_ptr<uint32_t[]>* order,
                std::vector<size_t>* start) {
  const size_t n = bins.size(), blocks = Blocks(n), k = static_cast<size_t>(num_bins);
  std::vector<size_t> at(blocks * k, 0);  // per block and bin: its count, then where its first position goes
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    for (size_t pos = b * kBlockPoints; pos < std::min(n, (b + 1) * kBlockPoints); ++pos) ++at[b * k + bins[pos]];
  });
  start->assign(k + 1, 0);
  size_t next = 0;
  for (size_t bin = 0; bin < k; ++bin) {
    (*start)[bin] = next;
    for (size_t b = 0; b < blocks; ++b) {
      const size_t count = at[b * k + bin];
      at[b * k + bin] = next;
      next += count;
    }
  }
  (*start)[k] = next;
  order->reset(new uint32_t[std::max<size_t>(n, 1)]);  // not zeroed: every entry is written, in parallel
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    size_t* where = &at[b * k];
    for (size_t pos = b * kBlockPoints; pos < std::min(n, (b + 1) * kBlockPoints); ++pos) {
      (*order)[where[bins[pos]]++] = static_cast<uint32_t>(pos);
    }
  });
}

// Per position in `points`: whether it is its cell's own point (the nearest to the cell's centre, ties to the
// first), and its group of cells.
void ChooseOnePerCell(const Cube& cube, const VoxelKey& node, const RecordView& records,
                      const std::vector<uint32_t>& points, std::vector<uint8_t>* chosen, std::vector<uint16_t>* group) {
  const size_t n = points.size();
  group->resize(n);
  const int group_level = node.level + kGroupBits;  // a group is a node's descendant at this level
  const int32_t origin[3] = {node.x << kGroupBits, node.y << kGroupBits, node.z << kGroupBits};
  ForEachPosition(n, [&](size_t pos) {
    int32_t stored[3];
    records.Stored(points[pos], stored);
    const VoxelKey key = cube.KeyOf(stored, group_level);
    (*group)[pos] = static_cast<uint16_t>((key.x - origin[0]) | (key.y - origin[1]) << kGroupBits |
                                          (key.z - origin[2]) << (2 * kGroupBits));
  });
  std::unique_ptr<uint32_t[]> order;
  std::vector<size_t> start;
  GroupByBin(*group, kGroups, &order, &start);
  chosen->resize(n);
  ForEachPosition(n, [&](size_t pos) { (*chosen)[pos] = 0; });
  tbb::enumerable_thread_specific<GroupTable> tables;
  tbb::parallel_for(0, kGroups, [&](int g) {
    if (start[g] == start[g + 1]) return;
    GroupTable& table = tables.local();
    int32_t stored[3];
    for (size_t k = start[g]; k < start[g + 1]; ++k) {
      const uint32_t pos = order[k];
      records.Stored(points[pos], stored);
      double d2 = 0.0;
      const int cell = CellInGroup(cube.CellOf(stored, node, &d2));
      Best& b = table.best[cell];
      if (b.pos_plus_1 == 0) table.filled.push_back(cell);
      if (b.pos_plus_1 == 0 || d2 < b.distance2) b = {pos + 1, d2};
    }
    for (const int cell : table.filled) {
      (*chosen)[table.best[cell].pos_plus_1 - 1] = 1;
      table.best[cell] = Best{};
    }
    table.filled.clear();
  });
}

// points[pos] for the positions order[first .. last).
std::vector<uint32_t> PointsAt(const std::vector<uint32_t>& points, const uint32_t* order, size_t first,
                               size_t last) {
  std::vector<uint32_t> out(last - first);
  ForEachPosition(out.size(), [&](size_t i) { out[i] = points[order[first + i]]; });
  return out;
}

// Splits `points` by bin (< num_bins) of each position, each part in the order of `points`.
std::vector<std::vector<uint32_t>> SplitByBin(const std::vector<uint32_t>& points, const std::vector<uint16_t>& bins,
                                              int num_bins) {
  std::unique_ptr<uint32_t[]> order;
  std::vector<size_t> start;
  GroupByBin(bins, num_bins, &order, &start);
  std::vector<std::vector<uint32_t>> parts(static_cast<size_t>(num_bins));
  for (int b = 0; b < num_bins; ++b) parts[b] = PointsAt(points, order.get(), start[b], start[b + 1]);
  return parts;
}

}  // namespace

std::vector<uint32_t> AllIndices(size_t n) {
  std::vector<uint32_t> indices(n);
  ForEachPosition(n, [&](size_t i) { indices[i] = static_cast<uint32_t>(i); });
  return indices;
}

void SelectOnePerCell(const Cube& cube, const VoxelKey& node, const RecordView& records,
                      const std::vector<uint32_t>& points, std::vector<uint32_t>* own, std::vector<uint32_t>* rest) {
  std::vector<uint8_t> chosen;
  std::vector<uint16_t> bins;
  ChooseOnePerCell(cube, node, records, points, &chosen, &bins);
  ForEachPosition(points.size(), [&](size_t pos) { bins[pos] = chosen[pos] ? 0 : 1; });
  std::vector<std::vector<uint32_t>> parts = SplitByBin(points, bins, 2);
  *own = std::move(parts[0]);
  *rest = std::move(parts[1]);
}

BuiltSubtree BuildSubtree(const Cube& cube, const VoxelKey& node, const RecordView& records,
                          std::vector<uint32_t> points, size_t max_points) {
  BuiltSubtree out;
  if (points.size() <= max_points || node.level >= cube.max_node_level()) {
    out.own = std::move(points);
    return out;
  }
  // Bins 0-7: the child octant of a point handed down; 8: the node's own points.
  std::vector<uint8_t> chosen;
  std::vector<uint16_t> bins;
  ChooseOnePerCell(cube, node, records, points, &chosen, &bins);
  ForEachPosition(points.size(), [&](size_t pos) {
    bins[pos] = static_cast<uint16_t>(chosen[pos] ? 8 : OctantOfGroup(bins[pos]));
  });
  std::vector<std::vector<uint32_t>> parts = SplitByBin(points, bins, 9);
  chosen = std::vector<uint8_t>();
  bins = std::vector<uint16_t>();
  out.own = std::move(parts[8]);
  size_t handed_down = 0;
  for (int o = 0; o < 8; ++o) handed_down += parts[o].size();
  points = std::vector<uint32_t>();
  const bool parallel = handed_down > kParallelPoints;
  std::array<BuiltSubtree, 8> built;
  const auto build = [&](size_t o) {
    if (!parts[o].empty()) {
      built[o] = BuildSubtree(cube, node.Child(static_cast<int>(o)), records, std::move(parts[o]), max_points);
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
