#pragma once
// Streaming decoder of the point data of a LAZ file (LASzip compressed data format) for LasReader: reads the
// chunk table, then batches of up to kBatchChunks consecutive chunks (at most kBatchPoints points, but always one
// whole chunk), decoded in parallel (chunks are independent in LAZ: one decoder per chunk of the batch), yielding
// uncompressed LAS point records in file order. Memory is bounded by one batch. Supports point formats 0-3 point-wise chunked (items version 2) and 6-8 layered chunked (version 3),
// with extra bytes, fixed or variable chunk sizes; anything else is refused with an InputError naming the file and
// the compressor/item version. Corrupt or truncated data give an InputError naming the file and the chunk.
// Private to io/.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/las_types.h"
#include "io/laz_vlr.h"

namespace sacfuse {

namespace laz {
class ChunkDecoder;
struct ChunkEntry;
}  // namespace laz

class LazPointReader {
 public:
  // `file` stays owned by the caller; `header` is the parsed LAS header (point format without the compression
  // bits), `laszip_vlr` the payload of the "laszip encoded" VLR.
  LazPointReader(const std::string& path, FILE* file, uint64_t file_size, const LasHeader& header,
                 const std::vector<uint8_t>& laszip_vlr);
  ~LazPointReader();
  // Decodes the next `count` records (count * record length bytes) into `records`. A corrupt chunk throws when the
  // reading reaches its first undecodable record, as a one-chunk-at-a-time decoder would: the records before it
  // are delivered first.
  void Read(uint8_t* records, size_t count);

  // The next chunk as stored, undecoded, and its point count, when no decoded records are pending (the reading
  // stands at a chunk's start); false at the end or mid-chunk. Read continues after it.
  bool ReadStoredChunk(std::vector<uint8_t>* bytes, uint64_t* points);

  static constexpr size_t kBatchChunks = 8;         // chunks decoded in parallel
  static constexpr uint64_t kBatchPoints = 400000;  // points of a batch (8 chunks of the usual 50,000)
  void Rewind();
  // Offset of the chunk table (EVLRs of LAS 1.4 LAZ files follow it).
  uint64_t chunk_table_offset() const { return table_offset_; }
  // Offset just past the chunk table: its entries coded again (the same coder, so the same length as written).
  uint64_t chunk_table_end() const { return table_end_; }

 private:
  [[noreturn]] void Fail(const std::string& message) const;
  void ReadAt(uint64_t position, uint8_t* out, size_t size) const;
  void ReadChunkTable(uint32_t chunk_size);
  // Reads the chunks from next_chunk_ on into batch_bytes_ and decodes them in parallel into batch_records_.
  void DecodeBatch();

  std::string path_;
  FILE* file_;
  uint64_t file_size_;
  size_t record_length_;
  uint64_t point_count_;
  uint64_t point_data_offset_;
  uint64_t table_offset_ = 0;
  uint64_t table_end_ = 0;
  laz::LazVlr vlr_;
  std::vector<std::unique_ptr<laz::ChunkDecoder>> decoders_;  // one per chunk of a batch, made when first needed
  struct Chunk {
    uint64_t start = 0;  // file offset
    uint64_t bytes = 0;
    uint64_t first_point = 0;
    uint64_t points = 0;
  };
  std::vector<Chunk> chunks_;
  size_t next_chunk_ = 0;              // first chunk of the next batch
  std::vector<uint8_t> batch_bytes_;   // the compressed chunks of the batch, as in the file
  std::vector<uint8_t> batch_records_;  // their decoded records
  size_t batch_pos_ = 0;               // records of the batch already handed out
  size_t batch_valid_ = 0;             // records of the batch decoded before its first error (all when none)
  std::string batch_error_;            // that error's message, empty when the whole batch decoded
};

}  // namespace sacfuse
