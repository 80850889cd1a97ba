#pragma once
// Point14 item, version 3 (LASzip compressed data format, "layered compression of LAS 1.4 points"): the 30
// leading bytes of point formats 6-10, coded in nine layers that each have their own arithmetic coder (so that
// a reader can skip fields): returns + X/Y, Z, classification, flags, intensity, scan angle, user data, point
// source ID, GPS time. Every scanner channel has its own context (models and previous point); the codec of the
// items that follow (RGB, NIR, extra bytes) switch contexts with it. Private to io/laz_*.
#include <array>
#include <cstdint>
#include <memory>

#include "io/laz_common.h"
#include "io/laz_gps_time.h"
#include "io/laz_integer.h"

namespace sacfuse::laz {

// The Point14 fields as the codec sees them.
struct Point14Fields {
  int32_t x = 0, y = 0, z = 0;
  uint16_t intensity = 0;
  uint32_t return_number = 0, number_of_returns = 0;  // 4 bits each
  uint32_t class_flags = 0;                           // synthetic, key-point, withheld, overlap
  uint32_t scanner_channel = 0;                       // 2 bits
  uint32_t scan_direction = 0, edge = 0;
  uint32_t classification = 0, user_data = 0;
  int16_t scan_angle = 0;
  uint16_t point_source = 0;
  uint64_t gps_time = 0;       // the double's bits
  bool gps_time_changed = false;  // codec state: did the time change at this point

  static Point14Fields FromRecord(const uint8_t* record);
  void ToRecord(uint8_t* record) const;
  uint32_t Flags() const { return (edge << 5) | (scan_direction << 4) | class_flags; }
};

enum Point14Layer {
  kLayerReturnsXY, kLayerZ, kLayerClassification, kLayerFlags, kLayerIntensity, kLayerScanAngle,
  kLayerUserData, kLayerPointSource, kLayerGpsTime, kPoint14Layers
};

class Point14Codec {
 public:
  static constexpr size_t kSize = 30;

  Point14Codec();
  ~Point14Codec();
  // Start of a chunk: `first` is the chunk's first record (stored raw); `present[layer]` says which layers the
  // chunk holds (decoding; absent layers repeat the previous value). The encoder passes all true.
  void Reset(const uint8_t* first, const std::array<bool, kPoint14Layers>& present);
  // Encoder: compresses *record. Decoder: writes the next record to *record. coders[layer]: kPoint14Layers coders.
  template <class Coder>
  void Code(Coder* coders, uint8_t* record);
  // Context the following items (RGB, NIR, extra bytes) use for the point just coded. Quirk of the format kept
  // for compatibility: it is the scanner channel only at the chunk's first point and at points where the channel
  // changed, and 0 otherwise (the reference implementations reset it to 0 before every point).
  uint32_t item_context() const { return item_context_; }
  // Encoder: whether a layer's value ever changed in this chunk (unchanged layers are not stored).
  bool changed(int layer) const { return changed_[layer]; }

 private:
  struct Context;
  void InitContext(uint32_t channel, const Point14Fields& from);
  template <class Coder>
  void CodeReturnsXY(Coder& coder, Context& c, const Point14Fields& in, uint32_t changed);

  std::array<std::unique_ptr<Context>, 4> contexts_;
  uint32_t current_ = 0;
  uint32_t item_context_ = 0;
  std::array<bool, kPoint14Layers> present_{};
  std::array<bool, kPoint14Layers> changed_{};
};

}  // namespace sacfuse::laz
