#include "io/laz_vlr.h"

#include "io/las_format.h"
#include "io/laz_arithmetic.h"

namespace sacfuse::laz {
namespace lf = las_format;

namespace {

constexpr size_t kFixedSize = 34;  // bytes before the item list
constexpr size_t kItemSize = 6;

std::string ItemName(uint16_t type) {
  switch (type) {
    case kItemByte: return "BYTE";
    case kItemPoint10: return "POINT10";
    case kItemGpsTime11: return "GPSTIME11";
    case kItemRgb12: return "RGB12";
    case kItemWavePacket13: return "WAVEPACKET13";
    case kItemPoint14: return "POINT14";
    case kItemRgb14: return "RGB14";
    case kItemRgbNir14: return "RGBNIR14";
    case kItemWavePacket14: return "WAVEPACKET14";
    case kItemByte14: return "BYTE14";
    default: return "item type " + std::to_string(type);
  }
}

}  // namespace

LazVlr LazVlr::ForFormat(int pdrf, uint16_t extra_bytes) {
  LazVlr vlr;
  if (pdrf >= 6) {
    vlr.compressor = kCompressorLayeredChunked;
    vlr.items.push_back({kItemPoint14, 30, 3});
    if (pdrf == 7) vlr.items.push_back({kItemRgb14, 6, 3});
    if (pdrf == 8) vlr.items.push_back({kItemRgbNir14, 8, 3});
    if (extra_bytes > 0) vlr.items.push_back({kItemByte14, extra_bytes, 3});
  } else {
    vlr.compressor = kCompressorPointwiseChunked;
    vlr.items.push_back({kItemPoint10, 20, 2});
    if (pdrf == 1 || pdrf == 3) vlr.items.push_back({kItemGpsTime11, 8, 2});
    if (pdrf == 2 || pdrf == 3) vlr.items.push_back({kItemRgb12, 6, 2});
    if (extra_bytes > 0) vlr.items.push_back({kItemByte, extra_bytes, 2});
  }
  return vlr;
}

std::vector<uint8_t> LazVlr::Serialize() const {
  std::vector<uint8_t> b(kFixedSize + kItemSize * items.size());
  lf::PutU16(&b[0], compressor);
  lf::PutU16(&b[2], coder);
  b[4] = version_major;
  b[5] = version_minor;
  lf::PutU16(&b[6], version_revision);
  lf::PutU32(&b[8], options);
  lf::PutU32(&b[12], chunk_size);
  lf::PutU64(&b[16], static_cast<uint64_t>(special_evlr_count));
  lf::PutU64(&b[24], static_cast<uint64_t>(special_evlr_offset));
  lf::PutU16(&b[32], static_cast<uint16_t>(items.size()));
  for (size_t i = 0; i < items.size(); ++i) {
    uint8_t* p = &b[kFixedSize + kItemSize * i];
    lf::PutU16(p, items[i].type);
    lf::PutU16(p + 2, items[i].size);
    lf::PutU16(p + 4, items[i].version);
  }
  return b;
}

LazVlr LazVlr::Parse(const std::vector<uint8_t>& b) {
  if (b.size() < kFixedSize) {
    throw DataError("laszip VLR of " + std::to_string(b.size()) + " bytes is shorter than 34 bytes");
  }
  LazVlr vlr;
  vlr.compressor = lf::GetU16(&b[0]);
  vlr.coder = lf::GetU16(&b[2]);
  vlr.version_major = b[4];
  vlr.version_minor = b[5];
  vlr.version_revision = lf::GetU16(&b[6]);
  vlr.options = lf::GetU32(&b[8]);
  vlr.chunk_size = lf::GetU32(&b[12]);
  vlr.special_evlr_count = static_cast<int64_t>(lf::GetU64(&b[16]));
  vlr.special_evlr_offset = static_cast<int64_t>(lf::GetU64(&b[24]));
  const size_t n = lf::GetU16(&b[32]);
  if (b.size() < kFixedSize + kItemSize * n) {
    throw DataError("laszip VLR lists " + std::to_string(n) + " items but has room for " +
                    std::to_string((b.size() - kFixedSize) / kItemSize));
  }
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = &b[kFixedSize + kItemSize * i];
    vlr.items.push_back({lf::GetU16(p), lf::GetU16(p + 2), lf::GetU16(p + 4)});
  }
  return vlr;
}

std::string LazVlr::Unsupported(int pdrf, size_t record_length) const {
  const std::string version = "LASzip " + std::to_string(version_major) + "." + std::to_string(version_minor) +
                              "r" + std::to_string(version_revision);
  if (coder != 0) return "coder " + std::to_string(coder) + " (" + version + ") is not the arithmetic coder";
  const bool layered = compressor == kCompressorLayeredChunked;
  if (compressor != kCompressorPointwiseChunked && !layered) {
    return "compressor " + std::to_string(compressor) + (compressor == 1 ? " (point-wise, not chunked)" : "") +
           " (" + version + ") is not supported (only point-wise chunked 2 and layered chunked 3)";
  }
  if (chunk_size == 0) return "chunk size 0";
  if (items.empty()) return "the laszip VLR lists no items";
  const uint16_t want_version = layered ? 3 : 2;
  size_t total = 0;
  size_t expected_index = 0;
  const LazVlr expected = ForFormat(pdrf, 0);
  for (const LazItem& item : items) {
    if (item.type == kItemWavePacket13 || item.type == kItemWavePacket14) {
      return "waveform packets (item " + ItemName(item.type) + " version " + std::to_string(item.version) + ", " +
             version + ") are not supported";
    }
  }
  for (const LazItem& item : items) {
    const std::string name = ItemName(item.type) + " version " + std::to_string(item.version);
    if (item.version != want_version) {
      return "item " + name + " (" + version + ", compressor " + std::to_string(compressor) +
             ") is not supported (point formats 0-3: point-wise version 2; 6-8: layered version 3)";
    }
    const bool extra = item.type == (layered ? kItemByte14 : kItemByte);
    if (extra) {
      if (&item != &items.back() || item.size == 0) return "item " + name + " must come last with a size > 0";
    } else {
      if (expected_index >= expected.items.size() || expected.items[expected_index].type != item.type ||
          expected.items[expected_index].size != item.size) {
        return "item " + name + " (size " + std::to_string(item.size) + ") does not fit point format " +
               std::to_string(pdrf) + " (waveform packets and other layouts are not supported)";
      }
      ++expected_index;
    }
    total += item.size;
  }
  if (expected_index != expected.items.size()) {
    return "the laszip items lack fields of point format " + std::to_string(pdrf);
  }
  if (total != record_length) {
    return "the laszip items describe " + std::to_string(total) + " bytes per point, the header " +
           std::to_string(record_length);
  }
  return "";
}

}  // namespace sacfuse::laz
