#pragma once
// The records of a COPC 1.0 file (Cloud Optimized Point Cloud, copc.io): a LAS 1.4 LAZ file with point format 6,
// 7 or 8 whose first VLR (at offset 375) is the 160-byte "copc"/1 info record and whose "copc"/1000 EVLR holds the
// octree hierarchy as pages of 32-byte entries. Each octree node's points are one LAZ chunk (the chunk table has
// variable point counts). Encoding and decoding only; io/copc_writer.h writes such files, io/copc_validate.h checks
// them. Private to io/.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sacfuse::copc {

constexpr size_t kInfoSize = 160;
constexpr size_t kEntrySize = 32;

// The info VLR's payload.
struct Info {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // of the octree's root cube, metres (unscaled)
  double halfsize = 0.0;                             // from the centre to any face of the root cube, metres
  double spacing = 0.0;                              // between points at the root level, metres; halved per level
  uint64_t root_hier_offset = 0;                     // file offset of the root hierarchy page
  uint64_t root_hier_size = 0;                       // its bytes
  double gpstime_minimum = 0.0;
  double gpstime_maximum = 0.0;
};
std::vector<uint8_t> EncodeInfo(const Info& info);
// "" and *info filled, or what is wrong (size, reserved words not zero, non-finite or non-positive cube).
std::string DecodeInfo(const std::vector<uint8_t>& payload, Info* info);

// An octree node: level 0 is the root cube; x, y, z in [0, 2^level).
struct VoxelKey {
  int32_t level = 0;
  int32_t x = 0;
  int32_t y = 0;
  int32_t z = 0;
  VoxelKey Parent() const { return {level - 1, x >> 1, y >> 1, z >> 1}; }
  // Octant bits: 1 = x, 2 = y, 4 = z.
  VoxelKey Child(int octant) const {
    return {level + 1, 2 * x + (octant & 1), 2 * y + ((octant >> 1) & 1), 2 * z + ((octant >> 2) & 1)};
  }
  bool Valid() const;  // level in [0, 30] and x, y, z in [0, 2^level)
  std::string ToString() const;  // "level-x-y-z", as EPT and COPC readers name nodes
  friend bool operator==(const VoxelKey& a, const VoxelKey& b) {
    return a.level == b.level && a.x == b.x && a.y == b.y && a.z == b.z;
  }
  friend bool operator<(const VoxelKey& a, const VoxelKey& b) {
    if (a.level != b.level) return a.level < b.level;
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
  }
};

// One hierarchy entry: point_count > 0: the node's chunk (absolute offset, bytes); -1: a child hierarchy page
// (absolute offset, bytes); 0: a node without points (offset and size 0) that has descendants.
struct Entry {
  VoxelKey key;
  uint64_t offset = 0;
  int32_t byte_size = 0;
  int32_t point_count = 0;
};
void AppendEntry(const Entry& entry, std::vector<uint8_t>* page);
Entry DecodeEntry(const uint8_t* bytes);  // kEntrySize bytes

// The bounds of `key`'s cube (min x, y, z, max x, y, z), metres, as COPC readers compute them from the info's
// centre and halfsize.
std::array<double, 6> NodeBounds(const Info& info, const VoxelKey& key);

}  // namespace sacfuse::copc
