#pragma once
// What LasWriter needs to write LAZ (LASzip compressed data format) instead of LAS: the "laszip encoded" VLR for
// the header, one compressed chunk per 50,000 records, and the chunk table that closes the point data. The file
// I/O stays LasWriter's. Private to io/.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "io/las_types.h"

namespace sacfuse {

namespace laz {
class ChunkEncoder;
struct ChunkEntry;
}  // namespace laz

class LazChunkWriter {
 public:
  static constexpr size_t kChunkPoints = 50000;
  // Point formats 0-3 (point-wise, items version 2) and 6-8 (layered, version 3); `record_length` may include
  // extra bytes.
  LazChunkWriter(int pdrf, size_t record_length);
  ~LazChunkWriter();
  LasVlr Vlr() const;
  // Chunks of records LasWriter buffers before it writes them. A constant: the order of the points of a merged file
  // (LasWriter::AppendLaz copies stored chunks ahead of the records still buffered) depends on it, so it must not
  // follow the thread count.
  static constexpr size_t kBatchChunks = 8;
  // Chunks of a batch compressed at once, in parallel, each with its own encoder: one per thread TBB may use when
  // the writer is made (tbb::global_control), at most kBatchChunks. Each encoder holds ~1.5 MB of models (8 were
  // 14 MB of aerial Montpellier's 200 MB heap on 2 threads, issue 13). Chunks are independent in LAZ, so the file is
  // the same for any number of encoders.
  size_t parallel_chunks() const { return encoders_.size(); }
  // Compresses `count` (1..kBatchChunks x kChunkPoints) records into consecutive chunks of kChunkPoints records
  // (the last may be shorter); the chunks' bytes, in order, stay valid until the next call.
  const std::vector<std::vector<uint8_t>>& Chunks(const uint8_t* records, size_t count);
  // Records a chunk of kChunkPoints records compressed elsewhere with this writer's VLR (copied from another
  // file), written by the caller after the chunks made so far.
  void AddStoredChunk(size_t bytes);
  // Bytes of all chunks made so far.
  uint64_t chunk_bytes() const { return total_bytes_; }
  // The chunk table of the chunks made so far.
  std::vector<uint8_t> Table() const;

 private:
  std::vector<uint8_t> vlr_payload_;
  std::vector<std::unique_ptr<laz::ChunkEncoder>> encoders_;  // one per chunk of a batch
  std::vector<std::vector<uint8_t>> chunks_;
  size_t record_length_ = 0;
  std::vector<laz::ChunkEntry> entries_;
  uint64_t total_bytes_ = 0;
};

}  // namespace sacfuse
