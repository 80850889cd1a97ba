#include "io/laz_chunk_writer.h"

#include <limits>

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
  encoder_ = std::make_unique<laz::ChunkEncoder>(vlr, record_length);
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

const std::vector<uint8_t>& LazChunkWriter::Chunk(const uint8_t* records, size_t count) {
  chunk_.clear();
  encoder_->Encode(records, count, &chunk_);
  if (chunk_.size() > std::numeric_limits<uint32_t>::max()) throw Error("LAZ chunk larger than 4 GiB");
  entries_.push_back({static_cast<uint32_t>(count), static_cast<uint32_t>(chunk_.size())});
  total_bytes_ += chunk_.size();
  return chunk_;
}

std::vector<uint8_t> LazChunkWriter::Table() const { return laz::EncodeChunkTable(entries_, false); }

}  // namespace sacfuse
