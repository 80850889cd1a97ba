#pragma once
// Point10 item, version 2 (LASzip compressed data format): the 20 leading bytes of point formats 0-5 (X, Y, Z,
// intensity, the return/flag byte, classification, scan angle rank, user data, point source ID), point-wise.
// Coordinates are predicted from the median of the last five differences in the same return context; the other
// fields are sent only when a "changed" mask says so. Private to io/laz_*.
#include <array>
#include <cstdint>

#include "io/laz_common.h"
#include "io/laz_integer.h"

namespace sacfuse::laz {

class Point10Codec {
 public:
  static constexpr size_t kSize = 20;

  Point10Codec();
  // Start of a chunk: `first` is the chunk's first item (stored raw).
  void Reset(const uint8_t* first);
  // Encoder: compresses *item. Decoder: writes the next item to *item.
  template <class Coder>
  void Code(Coder& coder, uint8_t* item);

 private:
  uint32_t ChangedMask(const uint8_t* item) const;

  std::array<uint8_t, kSize> last_{};
  std::array<uint16_t, 16> last_intensity_{};
  std::array<Median5, 16> median_x_;
  std::array<Median5, 16> median_y_;
  std::array<int32_t, 8> last_z_{};

  SymbolModel changed_{64};
  LazyModels<256> return_byte_{256};
  LazyModels<256> classification_{256};
  LazyModels<256> user_data_{256};
  std::array<SymbolModel, 2> scan_angle_{SymbolModel(256), SymbolModel(256)};
  IntegerCodec intensity_{16, 4};
  IntegerCodec point_source_{16, 1};
  IntegerCodec dx_{32, 2};
  IntegerCodec dy_{32, 22};
  IntegerCodec z_{32, 20};
};

}  // namespace sacfuse::laz
