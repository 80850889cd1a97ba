#pragma once
// The "laszip encoded" VLR (user ID "laszip encoded", record ID 22204) of the LASzip compressed data format:
// compressor (2 point-wise chunked, 3 layered chunked), coder (0 arithmetic), LASzip version, options, points per
// chunk (0xFFFFFFFF: variable, the chunk table then holds the counts), special EVLR count and offset (-1), and
// the list of items (type, size, version) a point record is made of. Private to io/.
#include <cstdint>
#include <string>
#include <vector>

namespace sacfuse::laz {

enum ItemType : uint16_t {
  kItemByte = 0, kItemPoint10 = 6, kItemGpsTime11 = 7, kItemRgb12 = 8, kItemWavePacket13 = 9,
  kItemPoint14 = 10, kItemRgb14 = 11, kItemRgbNir14 = 12, kItemWavePacket14 = 13, kItemByte14 = 14,
};

struct LazItem {
  uint16_t type = 0;
  uint16_t size = 0;
  uint16_t version = 0;
};

constexpr uint16_t kCompressorPointwiseChunked = 2;
constexpr uint16_t kCompressorLayeredChunked = 3;
constexpr uint32_t kVariableChunkSize = 0xFFFFFFFFu;
constexpr uint32_t kDefaultChunkSize = 50000;

struct LazVlr {
  uint16_t compressor = kCompressorPointwiseChunked;
  uint16_t coder = 0;
  uint8_t version_major = 3;
  uint8_t version_minor = 4;
  uint16_t version_revision = 3;
  uint32_t options = 0;
  uint32_t chunk_size = kDefaultChunkSize;
  int64_t special_evlr_count = -1;
  int64_t special_evlr_offset = -1;
  std::vector<LazItem> items;

  // What we write for point format `pdrf` (0-3: point-wise v2; 6-8: layered v3) with `extra_bytes` per record.
  static LazVlr ForFormat(int pdrf, uint16_t extra_bytes);
  std::vector<uint8_t> Serialize() const;
  // Throws laz::DataError on a malformed payload.
  static LazVlr Parse(const std::vector<uint8_t>& payload);
  // "" when our codecs decode records of `pdrf` with `record_length` bytes described by this VLR, else why not
  // (naming the compressor / item and version).
  std::string Unsupported(int pdrf, size_t record_length) const;
};

}  // namespace sacfuse::laz
