#include "io/laz_chunk_writer.h"

#include <algorithm>
#include <limits>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/las_format.h"
#include "io/laz_chunk_codec.h"
#include "io/laz_chunk_table.h"
#include "io/laz_vlr.h"

namespace sacfuse {
namespace lf = las_format;

LazChunkWriter::LazChunkWriter(int pdrf, size_t record_length) {
  const size_t base = lf::BaseRecordSize(pdrf);
  const laz::LazVlr vlr = laz::LazVlr::ForFormat(pdrf, static_cast<uint16_t>(record_length - base));
  const std::string unsupported = vlr.Unsupported(pdrf, record_length);
  if (!unsupported.empty()) throw Error("LAZ cannot be written for point format " + std::to_string(pdrf) + ": " + unsupported);
  vlr_payload_ = vlr.Serialize();
  record_length_ = record_length;
  const size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  const size_t encoders = std::clamp<size_t>(threads, 1, kBatchChunks);
  for (size_t i = 0; i < encoders; ++i) {
    encoders_.push_back(std::make_unique<laz::ChunkEncoder>(vlr, record_length));
  }
}

LazChunkWriter::~LazChunkWriter() = default;

LasVlr LazChunkWriter::Vlr() const {
  LasVlr vlr;
  vlr.user_id = lf::kLaszipUserId;
  vlr.record_id = lf::kLaszipRecordId;
  vlr.description = "sacfuse LAZ (LASzip format)";
  vlr.data = vlr_payload_;
  return vlr;
}

const std::vector<std::vector<uint8_t>>& LazChunkWriter::Chunks(const uint8_t* records, size_t count) {
  if (count == 0 || count > kBatchChunks * kChunkPoints) {
    throw Error("LAZ: invalid batch of " + std::to_string(count) + " records");
  }
  const size_t num_chunks = (count + kChunkPoints - 1) / kChunkPoints;
  chunks_.resize(num_chunks);
  // Encoder k codes chunks k, k + E, k + 2E, ... (E encoders): each chunk is coded by one encoder alone.
  const size_t num_encoders = std::min(encoders_.size(), num_chunks);
  tbb::parallel_for(size_t{0}, num_encoders, [&](size_t k) {
    for (size_t i = k; i < num_chunks; i += num_encoders) {
      const size_t first = i * kChunkPoints;
      // Coded into a vector of this task's own (chunks_[i]'s storage, swapped in and out): the chunks' vector
      // headers share cache lines, and a point-wise encoder appends byte by byte (false sharing).
      std::vector<uint8_t> bytes;
      bytes.swap(chunks_[i]);
      bytes.clear();
      encoders_[k]->Encode(records + first * record_length_, std::min(kChunkPoints, count - first), &bytes);
      chunks_[i].swap(bytes);
    }
  });
  for (size_t i = 0; i < num_chunks; ++i) {
    if (chunks_[i].size() > std::numeric_limits<uint32_t>::max()) throw Error("LAZ chunk larger than 4 GiB");
    const size_t points = std::min(kChunkPoints, count - i * kChunkPoints);
    entries_.push_back({static_cast<uint32_t>(points), static_cast<uint32_t>(chunks_[i].size())});
    total_bytes_ += chunks_[i].size();
  }
  return chunks_;
}

void LazChunkWriter::AddStoredChunk(size_t bytes) {
  if (bytes > std::numeric_limits<uint32_t>::max()) throw Error("LAZ chunk larger than 4 GiB");
  entries_.push_back({static_cast<uint32_t>(kChunkPoints), static_cast<uint32_t>(bytes)});
  total_bytes_ += bytes;
}

std::vector<uint8_t> LazChunkWriter::Table() const { return laz::EncodeChunkTable(entries_, false); }

}  // namespace sacfuse
