#pragma once
// The bytes of a COPC file, for io/copc_writer.h: the LAS 1.4 header, the VLRs (the COPC info VLR first, at offset
// 375; the "laszip encoded" VLR with variable chunk sizes last), one LAZ chunk per octree node in the order the
// nodes are written, the chunk table (point count and bytes of every chunk), the hierarchy EVLR
// (io/copc_hierarchy.h) and the other EVLRs. Written under a temporary name, fsynced and renamed into place by
// Finish(); destroyed unfinished, it removes the temporary file. Private to io/.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/copc_hierarchy.h"
#include "io/copc_octree.h"
#include "io/las_format.h"
#include "io/las_types.h"

namespace sacfuse::copc {

class CopcFile {
 public:
  // `header`: counts, bounds, returns, quantisation and identification of the points to come (the VLR fields
  // and the EVLR start are filled here). `vlrs`: the CRS and other records to carry (layout records are
  // dropped). `info`: the octree's cube and spacing.
  CopcFile(const std::string& path, const las_format::HeaderFields& header, const std::vector<LasVlr>& vlrs,
           const Info& info, const PageLayout& layout);
  ~CopcFile();
  CopcFile(const CopcFile&) = delete;
  CopcFile& operator=(const CopcFile&) = delete;

  // Compresses each node's points (indices into `records`) into one chunk, nodes in parallel, and appends the
  // chunks in the order given. A node without points gets a 0-point hierarchy entry (it must have descendants).
  void WriteNodes(const RecordView& records, const std::vector<BuiltNode>& nodes);
  // Points written so far; after Finish, the hierarchy's nodes, levels and pages.
  uint64_t points() const { return points_; }
  size_t nodes() const { return entries_.size(); }
  int levels() const;
  size_t pages() const { return pages_; }
  // Chunk table, hierarchy and EVLRs, header and info patched; fsync, rename. Throws Error when the points
  // written differ from the header's count.
  void Finish();

 private:
  struct Encoders;
  void Write(const uint8_t* data, size_t size);
  void WriteAt(uint64_t offset, const std::vector<uint8_t>& bytes);

  std::string path_;
  std::string temp_path_;
  FILE* file_ = nullptr;
  las_format::HeaderFields header_;
  std::vector<LasVlr> evlrs_;
  Info info_;
  PageLayout layout_;
  uint32_t info_payload_offset_ = 0;
  std::unique_ptr<Encoders> encoders_;
  std::vector<Entry> entries_;
  std::vector<std::pair<uint32_t, uint32_t>> chunks_;  // points, bytes (file order)
  uint64_t position_ = 0;  // bytes written
  uint64_t points_ = 0;
  size_t pages_ = 0;
  bool gps_seen_ = false;
  double gps_min_ = 0.0, gps_max_ = 0.0;
  bool finished_ = false;
};

}  // namespace sacfuse::copc
