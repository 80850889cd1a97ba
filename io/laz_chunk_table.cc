#include "io/laz_chunk_table.h"

#include "io/las_format.h"
#include "io/laz_arithmetic.h"
#include "io/laz_integer.h"

namespace sacfuse::laz {
namespace lf = las_format;

namespace {

constexpr uint32_t kPointsContext = 0;
constexpr uint32_t kBytesContext = 1;

template <class Coder>
void CodeEntries(Coder& coder, std::vector<ChunkEntry>& chunks, bool variable_size) {
  IntegerCodec ic(32, 2);
  ChunkEntry prev;
  for (ChunkEntry& e : chunks) {
    if (variable_size) {
      e.points = static_cast<uint32_t>(
          ic.Code(coder, static_cast<int32_t>(prev.points), static_cast<int32_t>(e.points), kPointsContext));
    }
    e.bytes = static_cast<uint32_t>(
        ic.Code(coder, static_cast<int32_t>(prev.bytes), static_cast<int32_t>(e.bytes), kBytesContext));
    prev = e;
  }
}

}  // namespace

std::vector<uint8_t> EncodeChunkTable(const std::vector<ChunkEntry>& chunks, bool variable_size) {
  std::vector<uint8_t> out(kChunkTableHeaderSize, 0);
  lf::PutU32(&out[0], 0);  // version
  lf::PutU32(&out[4], static_cast<uint32_t>(chunks.size()));
  if (!chunks.empty()) {
    std::vector<ChunkEntry> copy = chunks;
    Encoder encoder;
    encoder.Start(&out);
    CodeEntries(encoder, copy, variable_size);
    encoder.Finish();
  }
  return out;
}

std::vector<ChunkEntry> DecodeChunkTable(const uint8_t* data, size_t size, uint32_t count, bool variable_size) {
  std::vector<ChunkEntry> chunks(count);
  if (count == 0) return chunks;
  Decoder decoder;
  decoder.Start(data, size);
  CodeEntries(decoder, chunks, variable_size);
  return chunks;
}

}  // namespace sacfuse::laz
