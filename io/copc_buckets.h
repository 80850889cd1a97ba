#pragma once
// The out-of-core step of io/copc_writer.h: the point records of an uncompressed LAS file (the writer's spill)
// sorted by octree node into files of raw records ("buckets"), each small enough to be built in memory. Private
// to io/.
//
// A cloud of at most max_points points is one bucket, the root, read straight from the LAS file. A larger one is
// distributed to the nodes of level L = ceil(log4(3 N / max_points)) (aerial clouds are 2.5D: a level has ~4^L
// occupied nodes, and 3x leaves room for uneven density); a bucket still above max_points is distributed again to
// its descendants, until each fits or its node cannot be split (Cube::max_node_level). The records' nodes are
// computed in parallel, a block at a time; records are appended in input order, through write buffers of at most
// buffer_bytes in all, so the result does not depend on timing or threads.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/copc_octree.h"

namespace sacfuse::copc {

struct Bucket {
  VoxelKey key;
  std::string path;     // raw records
  uint64_t offset = 0;  // of the first record in `path`
  uint64_t points = 0;
};

// `las_path`: an uncompressed LAS file whose `count` records of `record_length` bytes start at `point_offset`.
// Bucket files go to `dir`. Throws Error on I/O errors (naming the file).
std::vector<Bucket> MakeBuckets(const std::string& las_path, uint64_t point_offset, uint64_t count,
                                size_t record_length, const Cube& cube, uint64_t max_points, size_t buffer_bytes,
                                const std::string& dir);

// The bucket's records (points x record_length bytes), read in parts in parallel. Throws Error on I/O errors.
std::unique_ptr<uint8_t[]> LoadBucket(const Bucket& bucket, size_t record_length);

}  // namespace sacfuse::copc
