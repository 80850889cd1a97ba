#include "io/laz_chunk_codec.h"

#include <cstring>
#include <optional>

#include "io/las_format.h"
#include "io/laz_arithmetic.h"
#include "io/laz_gps_time.h"
#include "io/laz_layered_items.h"
#include "io/laz_point10.h"
#include "io/laz_point14.h"
#include "io/laz_rgb.h"

namespace sacfuse::laz {
namespace lf = las_format;

// The item codecs of one record layout, with their byte offsets in the record.
struct ItemCodecs {
  // Point-wise (formats 0-3).
  std::optional<Point10Codec> point10;
  std::optional<GpsTimeCodec> gps;
  size_t gps_offset = 0;
  std::optional<RgbModels> rgb;
  std::array<uint16_t, 3> last_rgb{};
  size_t rgb_offset = 0;
  std::optional<BytesCodec> bytes;
  // Layered (formats 6-8).
  std::optional<Point14Codec> point14;
  std::optional<Rgb14Codec> rgb14;
  std::optional<Byte14Codec> byte14;
  size_t extra_offset = 0;  // of the BYTE / BYTE14 item

  ItemCodecs(const LazVlr& vlr) {
    size_t offset = 0;
    for (const LazItem& item : vlr.items) {
      switch (item.type) {
        case kItemPoint10: point10.emplace(); break;
        case kItemGpsTime11:
          gps.emplace(GpsTimeCodec::Variant::kPointwise2);
          gps_offset = offset;
          break;
        case kItemRgb12:
          rgb.emplace();
          rgb_offset = offset;
          break;
        case kItemByte:
          bytes.emplace(item.size);
          extra_offset = offset;
          break;
        case kItemPoint14: point14.emplace(); break;
        case kItemRgb14: rgb14.emplace(false); break;
        case kItemRgbNir14: rgb14.emplace(true); break;
        case kItemByte14:
          byte14.emplace(item.size);
          extra_offset = offset;
          break;
        default: break;  // LazVlr::Unsupported() refused it
      }
      offset += item.size;
    }
  }

  size_t layers() const {
    return kPoint14Layers + (rgb14 ? rgb14->layers() : 0) + (byte14 ? byte14->layers() : 0);
  }

  void ResetPointwise(const uint8_t* first) {
    point10->Reset(first);
    if (gps) gps->Reset(lf::GetU64(first + gps_offset));
    if (rgb) {
      rgb->Reset();
      for (int c = 0; c < 3; ++c) last_rgb[c] = lf::GetU16(first + rgb_offset + 2 * c);
    }
    if (bytes) bytes->Reset(first + extra_offset);
  }

  template <class Coder>
  void CodePointwise(Coder& coder, uint8_t* record) {
    constexpr bool kEnc = Coder::kEncoding;
    point10->Code(coder, record);
    if (gps) {
      const uint64_t t = gps->Code(coder, kEnc ? lf::GetU64(record + gps_offset) : 0);
      if (!kEnc) lf::PutU64(record + gps_offset, t);
    }
    if (rgb) {
      std::array<uint16_t, 3> value{};
      uint8_t* p = record + rgb_offset;
      if (kEnc) value = {lf::GetU16(p), lf::GetU16(p + 2), lf::GetU16(p + 4)};
      CodeRgb(coder, *rgb, last_rgb, value);
      if (!kEnc) {
        for (int c = 0; c < 3; ++c) lf::PutU16(p + 2 * c, value[c]);
      }
    }
    if (bytes) bytes->Code(coder, record + extra_offset);
  }

  // present: one flag per layer (Point14's, then the colour item's, then the extra bytes').
  void ResetLayered(const uint8_t* first, const std::vector<bool>& present) {
    std::array<bool, kPoint14Layers> p14;
    for (size_t i = 0; i < kPoint14Layers; ++i) p14[i] = present[i];
    point14->Reset(first, p14);
    const uint32_t context = point14->item_context();
    size_t layer = kPoint14Layers;
    bool flags[2] = {false, false};
    if (rgb14) {
      for (size_t i = 0; i < rgb14->layers(); ++i) flags[i] = present[layer + i];
      rgb14->Reset(first + Point14Codec::kSize, context, flags);
      layer += rgb14->layers();
    }
    if (byte14) {
      std::unique_ptr<bool[]> b(new bool[byte14->layers()]);
      for (size_t i = 0; i < byte14->layers(); ++i) b[i] = present[layer + i];
      byte14->Reset(first + extra_offset, context, b.get());
    }
  }

  template <class Coder>
  void CodeLayered(Coder* coders, uint8_t* record) {
    point14->Code(coders, record);
    const uint32_t context = point14->item_context();
    Coder* next = coders + kPoint14Layers;
    if (rgb14) {
      rgb14->Code(next, record + Point14Codec::kSize, context);
      next += rgb14->layers();
    }
    if (byte14) byte14->Code(next, record + extra_offset, context);
  }

  // Encoder: whether a layer is stored.
  bool LayerChanged(size_t layer) const {
    if (layer < kPoint14Layers) return point14->changed(static_cast<int>(layer));
    layer -= kPoint14Layers;
    if (rgb14) {
      if (layer < rgb14->layers()) return rgb14->changed(layer);
      layer -= rgb14->layers();
    }
    return byte14->changed(layer);
  }
};

// ------------------------------------------------------------------------------------------------ ChunkEncoder

ChunkEncoder::ChunkEncoder(const LazVlr& vlr, size_t record_length)
    : layered_(vlr.compressor == kCompressorLayeredChunked),
      record_length_(record_length),
      items_(std::make_unique<ItemCodecs>(vlr)) {
  if (layered_) layer_bytes_.resize(items_->layers());
}

ChunkEncoder::~ChunkEncoder() = default;

void ChunkEncoder::Encode(const uint8_t* records, size_t count, std::vector<uint8_t>* out) {
  out->insert(out->end(), records, records + record_length_);  // the first record, raw
  std::vector<uint8_t> scratch(records, records + record_length_);
  if (!layered_) {
    items_->ResetPointwise(scratch.data());
    Encoder encoder;
    encoder.Start(out);
    for (size_t i = 1; i < count; ++i) {
      std::memcpy(scratch.data(), records + i * record_length_, record_length_);
      items_->CodePointwise(encoder, scratch.data());
    }
    encoder.Finish();
    return;
  }
  const size_t n = layer_bytes_.size();
  items_->ResetLayered(scratch.data(), std::vector<bool>(n, true));
  std::vector<Encoder> encoders(n);
  for (size_t l = 0; l < n; ++l) {
    layer_bytes_[l].clear();
    encoders[l].Start(&layer_bytes_[l]);
  }
  for (size_t i = 1; i < count; ++i) {
    std::memcpy(scratch.data(), records + i * record_length_, record_length_);
    items_->CodeLayered(encoders.data(), scratch.data());
  }
  uint8_t word[4];
  lf::PutU32(word, static_cast<uint32_t>(count));
  out->insert(out->end(), word, word + 4);
  std::vector<bool> stored(n);
  for (size_t l = 0; l < n; ++l) {
    encoders[l].Finish();
    stored[l] = items_->LayerChanged(l);
    lf::PutU32(word, stored[l] ? static_cast<uint32_t>(layer_bytes_[l].size()) : 0u);
    out->insert(out->end(), word, word + 4);
  }
  for (size_t l = 0; l < n; ++l) {
    if (stored[l]) out->insert(out->end(), layer_bytes_[l].begin(), layer_bytes_[l].end());
  }
}

// ------------------------------------------------------------------------------------------------ ChunkDecoder

ChunkDecoder::ChunkDecoder(const LazVlr& vlr, size_t record_length)
    : layered_(vlr.compressor == kCompressorLayeredChunked),
      record_length_(record_length),
      items_(std::make_unique<ItemCodecs>(vlr)),
      first_(record_length) {}

ChunkDecoder::~ChunkDecoder() = default;

void ChunkDecoder::Start(const uint8_t* data, size_t size, uint64_t count) {
  if (size < record_length_) {
    throw DataError("chunk of " + std::to_string(size) + " bytes cannot hold its first point (" +
                    std::to_string(record_length_) + " bytes)");
  }
  std::memcpy(first_.data(), data, record_length_);
  count_ = count;
  next_ = 0;
  data += record_length_;
  size -= record_length_;
  if (!layered_) {
    items_->ResetPointwise(first_.data());
    pointwise_.Start(data, size);
    return;
  }
  const size_t n = items_->layers();
  if (size < 4 + 4 * n) throw DataError("chunk too short for its layer table");
  const uint32_t stored_count = lf::GetU32(data);
  if (stored_count != count) {
    throw DataError("chunk says it holds " + std::to_string(stored_count) + " points, the chunk table " +
                    std::to_string(count));
  }
  std::vector<uint64_t> sizes(n);
  uint64_t total = 0;
  for (size_t l = 0; l < n; ++l) {
    sizes[l] = lf::GetU32(data + 4 + 4 * l);
    total += sizes[l];
  }
  const uint8_t* layer = data + 4 + 4 * n;
  const uint64_t room = size - 4 - 4 * n;
  if (total > room) {
    throw DataError("chunk layers need " + std::to_string(total) + " bytes, the chunk has " + std::to_string(room));
  }
  std::vector<bool> present(n);
  layers_.assign(n, Decoder());
  for (size_t l = 0; l < n; ++l) {
    present[l] = sizes[l] > 0;
    if (present[l]) layers_[l].Start(layer, sizes[l]);
    layer += sizes[l];
  }
  if (count > 1 && !present[kLayerReturnsXY]) throw DataError("chunk lacks its returns/XY layer");
  items_->ResetLayered(first_.data(), present);
}

void ChunkDecoder::Next(uint8_t* record) {
  if (next_ >= count_) throw DataError("read past the end of a chunk");
  if (next_++ == 0) {
    std::memcpy(record, first_.data(), record_length_);
    return;
  }
  if (layered_) {
    items_->CodeLayered(layers_.data(), record);
  } else {
    items_->CodePointwise(pointwise_, record);
  }
}

}  // namespace sacfuse::laz
