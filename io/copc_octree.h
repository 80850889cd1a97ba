#pragma once
// The octree of a COPC file, in the integer space of the LAS quantisation, and how its nodes get their points
// (io/copc_writer.h builds files with it). Private to io/.
//
// Cube: a point with stored integer X lies at p = 2 X + 1 half-quanta (odd). The root cube spans
// [min, min + side) on every axis, min even, side = c 2^k with 8 <= c < 16, centred on the points' bounds (COPC
// readers expect the cube's centre inside the header's bounds). A node of level L <= max_node_level() = k - 1 has
// even boundaries, so no point lies on one: a point's node is exact integer arithmetic, nested across levels
// (the parent of its key at L + 1 is its key at L), and a reader's floating-point node bounds contain it with half
// a quantum to spare.
//
// Points of a node: each node has kCells^3 cells (kCells = 128 per axis, as untwine; the COPC spacing is the
// root's side / kCells). Built top-down: a node with at most max_points points keeps them all (a leaf); a larger
// one keeps, of each occupied cell, the point nearest the cell's centre (ties: the first), and hands the rest to
// its eight children. So every point is in exactly one node, and the points of the upper levels are a spatially
// even subsample, one per cell. Across buckets that were built separately (out of core) the same per-cell choice
// runs bottom-up: a parent keeps one per cell of its children's own points.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "io/copc_format.h"

namespace sacfuse::copc {

constexpr int kCellBits = 7;
constexpr int kCells = 1 << kCellBits;

class Cube {
 public:
  Cube() = default;
  // The smallest cube of the form above around points with stored integers in [lo, hi] (lo <= hi per axis).
  static Cube Around(const std::array<int32_t, 3>& lo, const std::array<int32_t, 3>& hi);

  // Deepest level whose nodes may hold points or be split into children.
  int max_node_level() const { return k_ - 1; }
  // Key of stored integer coordinates at `level` (0 <= level <= max_node_level() + kCellBits).
  VoxelKey KeyOf(const int32_t stored[3], int level) const;
  // The node's cell of a point (0 .. kCells^3 - 1) and its squared distance from that cell's centre, in
  // half-quanta^2.
  uint32_t CellOf(const int32_t stored[3], const VoxelKey& node, double* distance2) const;
  // Octant (1 = x, 2 = y, 4 = z) of the child of `node` holding the point.
  int OctantOf(const int32_t stored[3], const VoxelKey& node) const;

  // Centre, halfsize and spacing in metres for a file with this quantisation (equal scale on every axis).
  Info ToInfo(double scale, const Eigen::Vector3d& offset) const;

 private:
  uint64_t Coordinate(int axis, int32_t stored, int level) const;

  std::array<int64_t, 3> min_ = {0, 0, 0};  // half-quanta, even
  uint64_t c_ = 8;                           // side = c_ << k_
  int k_ = 2;
};

// Point records held in memory (LAS point data records, stored X, Y, Z as int32 at bytes 0, 4, 8).
struct RecordView {
  const uint8_t* data = nullptr;
  size_t record_length = 0;
  void Stored(uint32_t i, int32_t out[3]) const;
};

// 0, 1, ..., n - 1 (filled in parallel).
std::vector<uint32_t> AllIndices(size_t n);

// Splits `points` (indices into `records`) of `node` into its own points (one per occupied cell: the point
// nearest the cell's centre, ties to the first in `points`) and the rest, both in the order of `points`. In
// parallel: the cells are chosen in 512 groups of 16^3 cells (each group's points alone, in a table of its
// cells), the points sorted into groups and parts by parallel stable counting; the result is a serial pass's.
void SelectOnePerCell(const Cube& cube, const VoxelKey& node, const RecordView& records,
                      const std::vector<uint32_t>& points, std::vector<uint32_t>* own, std::vector<uint32_t>* rest);

// A node and its points (indices into the records), as built.
struct BuiltNode {
  VoxelKey key;
  std::vector<uint32_t> points;
};
struct BuiltSubtree {
  std::vector<uint32_t> own;           // the subtree root's own points
  std::vector<BuiltNode> descendants;  // every other node of the subtree with points, children before parents
};

// Builds the subtree under `node` from all its points (top-down, as described above): each node's points split
// as SelectOnePerCell does, children built in parallel when large. The result is the same for any thread count.
BuiltSubtree BuildSubtree(const Cube& cube, const VoxelKey& node, const RecordView& records,
                          std::vector<uint32_t> points, size_t max_points);

}  // namespace sacfuse::copc
