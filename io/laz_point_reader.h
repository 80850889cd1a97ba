#pragma once
// Streaming decoder of the point data of a LAZ file (LASzip compressed data format) for LasReader: reads the
// chunk table, then one chunk at a time (memory bounded by the largest chunk), yielding uncompressed LAS point
// records. Supports point formats 0-3 point-wise chunked (items version 2) and 6-8 layered chunked (version 3),
// with extra bytes, fixed or variable chunk sizes; anything else is refused with an InputError naming the file and
// the compressor/item version. Corrupt or truncated data give an InputError naming the file and the chunk.
// Private to io/.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/las_types.h"

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
  // Decodes the next `count` records (count * record length bytes) into `records`.
  void Read(uint8_t* records, size_t count);
  void Rewind();
  // Offset of the chunk table (EVLRs of LAS 1.4 LAZ files follow it).
  uint64_t chunk_table_offset() const { return table_offset_; }

 private:
  [[noreturn]] void Fail(const std::string& message) const;
  void ReadAt(uint64_t position, uint8_t* out, size_t size) const;
  void ReadChunkTable(uint32_t chunk_size);
  void StartChunk(size_t index);

  std::string path_;
  FILE* file_;
  uint64_t file_size_;
  size_t record_length_;
  uint64_t point_count_;
  uint64_t point_data_offset_;
  uint64_t table_offset_ = 0;
  std::unique_ptr<laz::ChunkDecoder> decoder_;
  struct Chunk {
    uint64_t start = 0;  // file offset
    uint64_t bytes = 0;
    uint64_t first_point = 0;
    uint64_t points = 0;
  };
  std::vector<Chunk> chunks_;
  std::vector<uint8_t> chunk_bytes_;
  size_t chunk_ = 0;             // chunk being decoded
  uint64_t left_in_chunk_ = 0;  // points of it still to decode
  bool started_ = false;
};

}  // namespace sacfuse
