#pragma once
// Streaming decoder of the point data of a LAZ file (LASzip compressed data format) for LasReader: reads the
// chunk table, then batches of consecutive chunks, decoded in parallel (chunks are independent in LAZ: one decoder
// per chunk of the batch), yielding uncompressed LAS point records in file order, handed out in place (Next: no
// copy on the caller's thread). A batch holds two chunks per thread of the task arena the reader was made in, at
// least kMinBatchChunks (at most that many times kChunkPoints points, but always one whole chunk), so that every
// thread has chunks to decode on any core count. While the reader hands out one batch, the next one is decoded in
// the background (read-ahead), so the caller's own work on the points overlaps the decoding instead of leaving the
// other threads idle (issue 48). Memory is bounded by two batches: 2 x 2 x 50,000 records (~7 MB of 34-byte
// records) and two chunk decoders (~1.5 MB of models each) per thread. Supports point formats 0-3 point-wise
// chunked (items version 2) and 6-8 layered chunked (version 3),
// with extra bytes, fixed or variable chunk sizes; anything else is refused with an InputError naming the file and
// the compressor/item version. Corrupt or truncated data give an InputError naming the file and the chunk.
// Private to io/.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <tbb/task_group.h>

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
  // The next decoded records, at least one and at most `max` (> 0; fewer where the current batch ends): *count of
  // them, record after record, in the reader's own buffer, valid until the next call of a method of the reader.
  // Throws past the last point. A corrupt chunk throws when the reading reaches its first undecodable record, as
  // a one-chunk-at-a-time decoder would: the records before it are delivered first.
  const uint8_t* Next(size_t max, size_t* count);

  // The next chunk as stored, undecoded, and its point count, when no decoded records are pending (the reading
  // stands at a chunk's start); false at the end or mid-chunk. Read continues after it.
  bool ReadStoredChunk(std::vector<uint8_t>* bytes, uint64_t* points);
  // Passes over the next `chunks` chunks as ReadStoredChunk would read them, adding their points to `*points`;
  // false, having moved nothing, where ReadStoredChunk would fail or when fewer chunks are left.
  bool SkipStoredChunks(uint64_t chunks, uint64_t* points);

  static constexpr size_t kMinBatchChunks = 8;       // chunks decoded in parallel on up to 4 threads
  static constexpr size_t kBatchChunksPerThread = 2;  // above 4 threads: two chunks per thread
  // Chunks of a batch for `threads` threads. The reader takes the threads TBB may use where it is made (the task
  // arena's, within tbb::global_control's limit).
  static size_t BatchChunks(size_t threads);
  size_t batch_chunks() const { return batch_chunks_; }
  void Rewind();
  // Offset of the chunk table (EVLRs of LAS 1.4 LAZ files follow it).
  uint64_t chunk_table_offset() const { return table_offset_; }
  // Offset just past the chunk table: its entries coded again (the same coder, so the same length as written).
  uint64_t chunk_table_end() const { return table_end_; }

 private:
  // Decoded records of consecutive chunks [first_chunk, end_chunk).
  struct Batch {
    size_t first_chunk = 0, end_chunk = 0;
    std::vector<uint8_t> bytes;              // the compressed chunks, as in the file
    std::unique_ptr<uint8_t[]> records;      // their decoded records
    size_t capacity = 0;                     // bytes of records
    size_t valid = 0;                        // records decoded before the batch's first error (all when none)
    std::string error;                       // that error's message, empty when the whole batch decoded
  };

  [[noreturn]] void Fail(const std::string& message) const;
  void ReadAt(uint64_t position, uint8_t* out, size_t size) const;
  void ReadChunkTable(uint32_t chunk_size);
  // Reads the chunks from `first` on into batch->bytes and decodes them in parallel into batch->records.
  void DecodeBatch(size_t first, Batch* batch);
  // Makes the batch starting at next_chunk_ current (the read-ahead's when it has it), then starts the read-ahead
  // of the batch after it.
  void NextBatch();
  // Waits for a running read-ahead. `keep`: its batch becomes usable (its I/O error is rethrown); else it is
  // dropped, error included.
  void WaitForReadAhead(bool keep);

  std::string path_;
  FILE* file_;
  uint64_t file_size_;
  size_t record_length_;
  uint64_t point_count_;
  uint64_t point_data_offset_;
  uint64_t table_offset_ = 0;
  uint64_t table_end_ = 0;
  size_t batch_chunks_ = kMinBatchChunks;
  laz::LazVlr vlr_;
  // One per chunk of a batch, made when first needed; used by one batch's decoding at a time.
  std::vector<std::unique_ptr<laz::ChunkDecoder>> decoders_;
  struct Chunk {
    uint64_t start = 0;  // file offset
    uint64_t bytes = 0;
    uint64_t first_point = 0;
    uint64_t points = 0;
  };
  std::vector<Chunk> chunks_;
  size_t next_chunk_ = 0;  // first chunk after the current batch (and after the chunks read as stored)
  Batch current_;
  size_t pos_ = 0;  // records of the current batch already handed out
  Batch ahead_;     // the read-ahead: decoding in the background (ahead_running_) or done (ahead_ready_)
  bool ahead_running_ = false;
  bool ahead_ready_ = false;
  std::exception_ptr ahead_failure_;  // the read-ahead's I/O error, rethrown when the reading gets there
  std::unique_ptr<tbb::task_group> ahead_task_;
};

}  // namespace sacfuse
