#include "io/laz_point_reader.h"

#include <cerrno>
#include <algorithm>
#include <cstring>
#include <utility>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "io/las_format.h"
#include "io/laz_arithmetic.h"
#include "io/laz_chunk_codec.h"
#include "io/laz_chunk_writer.h"
#include "io/laz_chunk_table.h"
#include "io/laz_vlr.h"

namespace sacfuse {
namespace lf = las_format;

namespace {

constexpr size_t kMaxTableBytesPerChunk = 32;  // generous bound of one coded table entry (two 32-bit integers)

}  // namespace

LazPointReader::LazPointReader(const std::string& path, FILE* file, uint64_t file_size, const LasHeader& header,
                               const std::vector<uint8_t>& laszip_vlr)
    : path_(path),
      file_(file),
      file_size_(file_size),
      record_length_(header.point_record_length),
      point_count_(header.point_count),
      point_data_offset_(header.offset_to_point_data),
      batch_chunks_(BatchChunks(std::min<size_t>(
          static_cast<size_t>(tbb::this_task_arena::max_concurrency()),
          tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)))) {
  laz::LazVlr& vlr = vlr_;
  try {
    vlr = laz::LazVlr::Parse(laszip_vlr);
  } catch (const laz::DataError& e) {
    Fail(std::string("LAZ: ") + e.what());
  }
  const std::string unsupported = vlr.Unsupported(header.point_format, record_length_);
  if (!unsupported.empty()) {
    Fail("LAZ point format " + std::to_string(header.point_format) + ": " + unsupported +
         "; decompress it with laszip or pdal first");
  }
  ReadChunkTable(vlr.chunk_size);
}

LazPointReader::~LazPointReader() {
  if (ahead_running_) ahead_task_->wait();  // the task catches its own exceptions
}

size_t LazPointReader::BatchChunks(size_t threads) {
  return std::max(kMinBatchChunks, kBatchChunksPerThread * threads);
}

void LazPointReader::Fail(const std::string& message) const { throw InputError(path_, message); }

void LazPointReader::ReadAt(uint64_t position, uint8_t* out, size_t size) const {
  if (position > file_size_ || size > file_size_ - position) {
    Fail("LAZ: " + std::to_string(size) + " bytes at offset " + std::to_string(position) +
         " run past the end of the file (" + std::to_string(file_size_) + " bytes; truncated?)");
  }
  if (size == 0) return;
  if (fseeko(file_, static_cast<off_t>(position), SEEK_SET) != 0 || std::fread(out, 1, size, file_) != size) {
    Fail("cannot read " + std::to_string(size) + " bytes at offset " + std::to_string(position) + ": " +
         std::strerror(errno));
  }
}

void LazPointReader::ReadChunkTable(uint32_t chunk_size) {
  const bool variable = chunk_size == laz::kVariableChunkSize;
  uint8_t word[8];
  // The point data open with the chunk table's offset (-1: written at the very end of the file by a streaming
  // writer); the chunks follow.
  const uint64_t chunks_start = point_data_offset_ + 8;
  {
    ReadAt(point_data_offset_, word, 8);
    int64_t offset = static_cast<int64_t>(lf::GetU64(word));
    if (offset == -1) {
      if (file_size_ < chunks_start + 8) Fail("LAZ: no chunk table offset at the end of the file (truncated?)");
      ReadAt(file_size_ - 8, word, 8);
      offset = static_cast<int64_t>(lf::GetU64(word));
    }
    if (offset < static_cast<int64_t>(chunks_start) ||
        static_cast<uint64_t>(offset) + laz::kChunkTableHeaderSize > file_size_) {
      Fail("LAZ: the chunk table offset " + std::to_string(offset) + " is outside the file (" +
           std::to_string(file_size_) + " bytes): truncated, or written by an interrupted compressor");
    }
    table_offset_ = static_cast<uint64_t>(offset);
  }
  ReadAt(table_offset_, word, 8);
  if (lf::GetU32(word) != 0) Fail("LAZ: chunk table version " + std::to_string(lf::GetU32(word)) + " (expected 0)");
  const uint32_t count = lf::GetU32(word + 4);
  const uint64_t expected = variable ? 0 : (point_count_ + chunk_size - 1) / chunk_size;
  if ((!variable && count != expected) || (variable && count > point_count_)) {
    Fail("LAZ: the chunk table lists " + std::to_string(count) + " chunks for " + std::to_string(point_count_) +
         " points" + (variable ? "" : " of " + std::to_string(chunk_size) + " a chunk") + " (corrupt)");
  }
  // Every chunk stores at least its first record raw: more chunks than that cannot fit.
  if (count > (table_offset_ - chunks_start) / record_length_) {
    Fail("LAZ: the chunk table lists " + std::to_string(count) + " chunks, more than fit in " +
         std::to_string(table_offset_ - chunks_start) + " bytes of point data (corrupt)");
  }
  const uint64_t stream_start = table_offset_ + laz::kChunkTableHeaderSize;
  std::vector<uint8_t> stream(
      static_cast<size_t>(std::min<uint64_t>(file_size_ - stream_start, kMaxTableBytesPerChunk * uint64_t{count} + 64)));
  ReadAt(stream_start, stream.data(), stream.size());
  std::vector<laz::ChunkEntry> entries;
  try {
    entries = laz::DecodeChunkTable(stream.data(), stream.size(), count, variable);
  } catch (const laz::DataError& e) {
    Fail(std::string("LAZ chunk table: ") + e.what());
  }
  table_end_ = table_offset_ + laz::EncodeChunkTable(entries, variable).size();
  uint64_t start = chunks_start;
  uint64_t first = 0;
  chunks_.clear();
  for (uint32_t i = 0; i < count; ++i) {
    Chunk c;
    c.start = start;
    c.bytes = entries[i].bytes;
    c.first_point = first;
    c.points = variable ? entries[i].points : std::min<uint64_t>(chunk_size, point_count_ - first);
    if (c.bytes > table_offset_ - start) {
      Fail("LAZ chunk " + std::to_string(i) + " of " + std::to_string(count) + " (" + std::to_string(c.bytes) +
           " bytes at offset " + std::to_string(start) + ") runs into the chunk table (corrupt chunk table)");
    }
    if (c.points == 0) Fail("LAZ chunk " + std::to_string(i) + " holds no points (corrupt chunk table)");
    start += c.bytes;
    first += c.points;
    chunks_.push_back(c);
  }
  if (first != point_count_) {
    Fail("LAZ: the chunks hold " + std::to_string(first) + " points, the header says " +
         std::to_string(point_count_));
  }
}

void LazPointReader::DecodeBatch(size_t first, Batch* batch) {
  size_t last = first + 1;  // one past the batch's last chunk
  uint64_t points = chunks_[first].points;
  const uint64_t batch_points = uint64_t{LazChunkWriter::kChunkPoints} * batch_chunks_;  // the usual chunk's
  while (last < chunks_.size() && last - first < batch_chunks_ && points + chunks_[last].points <= batch_points) {
    points += chunks_[last].points;
    ++last;
  }
  const size_t n = last - first;
  // The chunks lie one after the other in the file: one read for the batch, before any thread starts.
  const uint64_t begin = chunks_[first].start;
  batch->bytes.resize(static_cast<size_t>(chunks_[last - 1].start + chunks_[last - 1].bytes - begin));
  ReadAt(begin, batch->bytes.data(), batch->bytes.size());
  // Not zero-filled: every record the reading hands out is written by its chunk's decoder first (in parallel).
  const size_t record_bytes = static_cast<size_t>(points) * record_length_;
  if (record_bytes > batch->capacity) {
    batch->records.reset(new uint8_t[record_bytes]);
    batch->capacity = record_bytes;
  }
  if (decoders_.size() < n) decoders_.resize(n);  // made by the chunks' tasks (their models are megabytes)
  std::vector<uint64_t> decoded(n, 0);  // records of each chunk decoded before an error
  std::vector<std::string> errors(n);
  tbb::parallel_for(size_t{0}, n, [&](size_t i) {
    const Chunk& c = chunks_[first + i];
    const uint8_t* bytes = batch->bytes.data() + (c.start - begin);
    uint8_t* out = batch->records.get() + (c.first_point - chunks_[first].first_point) * record_length_;
    if (!decoders_[i]) decoders_[i] = std::make_unique<laz::ChunkDecoder>(vlr_, record_length_);
    const std::string name = "LAZ chunk " + std::to_string(first + i) + " of " + std::to_string(chunks_.size());
    try {
      decoders_[i]->Start(bytes, static_cast<size_t>(c.bytes), c.points);
    } catch (const laz::DataError& e) {
      errors[i] = name + ": " + e.what();
      return;
    }
    // Counted in a local: decoded[i] shares a cache line with the other chunks' counts, and a store to it per
    // record made the threads decoding neighbouring chunks wait for each other (false sharing).
    uint64_t done = 0;
    try {
      for (; done < c.points; ++done) decoders_[i]->Next(out + done * record_length_);
    } catch (const laz::DataError& e) {
      errors[i] = name + " (points " + std::to_string(c.first_point) + ".." +
                  std::to_string(c.first_point + c.points - 1) + "): " + e.what();
    }
    decoded[i] = done;
  });
  // The records up to the first error, in file order; the error is raised when the reading gets there.
  batch->first_chunk = first;
  batch->end_chunk = last;
  batch->valid = 0;
  batch->error.clear();
  for (size_t i = 0; i < n; ++i) {
    batch->valid += static_cast<size_t>(decoded[i]);
    if (!errors[i].empty()) {
      batch->error = errors[i];
      break;
    }
  }
}

void LazPointReader::WaitForReadAhead(bool keep) {
  if (!ahead_running_) return;
  ahead_task_->wait();  // the task catches its own exceptions: this never throws
  ahead_running_ = false;
  ahead_ready_ = keep && !ahead_failure_;
  if (!keep) ahead_failure_ = nullptr;
  if (ahead_failure_) std::rethrow_exception(std::exchange(ahead_failure_, nullptr));
}

void LazPointReader::NextBatch() {
  if (next_chunk_ >= chunks_.size()) Fail("LAZ: read past the last point");
  WaitForReadAhead(/*keep=*/true);
  if (ahead_ready_ && ahead_.first_chunk == next_chunk_) {
    std::swap(current_, ahead_);
  } else {
    DecodeBatch(next_chunk_, &current_);
  }
  ahead_ready_ = false;
  pos_ = 0;
  next_chunk_ = current_.end_chunk;
  // The next batch in the background, unless this one ends the file or breaks off at an error.
  if (next_chunk_ < chunks_.size() && current_.error.empty()) {
    if (!ahead_task_) ahead_task_ = std::make_unique<tbb::task_group>();
    ahead_running_ = true;
    const size_t first = next_chunk_;
    ahead_task_->run([this, first] {
      try {
        DecodeBatch(first, &ahead_);
      } catch (...) {
        ahead_failure_ = std::current_exception();
      }
    });
  }
}

const uint8_t* LazPointReader::Next(size_t max, size_t* count) {
  while (pos_ == current_.valid) {
    if (!current_.error.empty()) Fail(current_.error);
    NextBatch();
  }
  *count = std::min(max, current_.valid - pos_);
  const uint8_t* records = current_.records.get() + pos_ * record_length_;
  pos_ += *count;
  return records;
}

bool LazPointReader::ReadStoredChunk(std::vector<uint8_t>* bytes, uint64_t* points) {
  if (pos_ != current_.valid || !current_.error.empty() || next_chunk_ >= chunks_.size()) return false;
  WaitForReadAhead(/*keep=*/false);  // it decoded this chunk: dropped, the file is the caller's again
  ahead_ready_ = false;
  const Chunk& c = chunks_[next_chunk_];
  bytes->resize(static_cast<size_t>(c.bytes));
  ReadAt(c.start, bytes->data(), bytes->size());
  *points = c.points;
  ++next_chunk_;
  return true;
}

bool LazPointReader::SkipStoredChunks(uint64_t chunks, uint64_t* points) {
  if (pos_ != current_.valid || !current_.error.empty() || chunks > chunks_.size() - next_chunk_) return false;
  if (chunks == 0) return true;
  WaitForReadAhead(/*keep=*/false);
  ahead_ready_ = false;
  for (uint64_t i = 0; i < chunks; ++i) *points += chunks_[next_chunk_++].points;
  return true;
}

void LazPointReader::Rewind() {
  WaitForReadAhead(/*keep=*/false);
  ahead_ready_ = false;
  next_chunk_ = 0;
  pos_ = 0;
  current_.valid = 0;
  current_.error.clear();
}

}  // namespace sacfuse
