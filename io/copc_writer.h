#pragma once
// Writes a COPC 1.0 file (Cloud Optimized Point Cloud, copc.io): LAS 1.4 LAZ, point format 6-8, the points in an
// octree whose nodes are LAZ chunks a viewer fetches by range (QGIS, potree, PDAL's readers.copc), the
// upper levels a spatially even subsample, every point in exactly one node (io/copc_octree.h).
//
// Out of core: points are streamed to an uncompressed spill file (a LasWriter, so every LAS rule and message is
// the LAS writer's), then at Close() sorted by octree node into bucket files each built in memory
// (io/copc_buckets.h), and the nodes above the buckets built from the buckets' top points. Memory: about
// memory_bytes for the points held at once, whatever the cloud's size; disk: the spill and the buckets, each about
// count x record length (36 B a point for format 7), in a work folder that is removed at the end. The file is
// written under a temporary name, fsynced and renamed: a killed writer leaves no file at the path, only its
// "<name>.tmp-<pid>-<n>" work folder and temporary file, which RemoveTemporaryFiles (io/atomic_file.h) deletes.
// The same points and options give the same file for any thread count.
#include <cstdint>
#include <memory>
#include <string>

#include "core/point.h"
#include "io/las_types.h"
#include "io/las_writer.h"

namespace sacfuse {

struct CopcOptions {
  // Points held in memory at once (buckets and nodes being built), bytes; ~96 B a point of format 7.
  uint64_t memory_bytes = uint64_t{1} << 30;
  // Folder for the spill and bucket files; "" = the output file's folder.
  std::string temp_dir;
  // A node with more points than this is split (its own points then one per cell of its 128^3 grid).
  size_t max_node_points = 100000;
  // Hierarchy pages (io/copc_hierarchy.h): a page every page_levels levels for subtrees of at least
  // min_page_entries nodes.
  int page_levels = 4;
  size_t min_page_entries = 64;
};

class CopcWriter : public PointSink {
 public:
  // `las`: LAS 1.4 with point format 6, 7 or 8 (unset: 7) and the same scale on every axis; `compressed` is
  // ignored (COPC is LAZ). Throws Error for other options, or when the work folder cannot be made.
  CopcWriter(const std::string& path, const LasWriterOptions& las, const CopcOptions& copc = {});
  ~CopcWriter() override;  // removes the work folder and any temporary file unless Close() succeeded
  CopcWriter(const CopcWriter&) = delete;
  CopcWriter& operator=(const CopcWriter&) = delete;

  // As LasWriter::Write and LasWriter::WritePoints (the same checks and messages).
  void Write(const FusedPoint* points, size_t count) override;
  void WritePoints(const LasPoint* points, size_t count);
  // Builds the octree and writes the file; throws on I/O errors (and leaves no file at the path).
  void Close();

  uint64_t num_points() const;
  const std::string& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sacfuse
