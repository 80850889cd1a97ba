#pragma once
// GPS time coding of the LASzip format: GpsTime11 item version 2 (point-wise) and the GPS time layer of Point14
// version 3. Times are coded as 64-bit integers (the double's bits): a difference that fits 32 bits is predicted
// as a multiple of the previous difference; otherwise the high half is coded against the previous one and the
// low half sent raw, opening one of four interleaved time sequences (for interleaved flight lines).
// Version 3 has no "unchanged" code (the Point14 layer sends a time only when it changed). Private to io/laz_*.
#include <array>
#include <cstdint>

#include "io/laz_integer.h"
#include "io/laz_models.h"

namespace sacfuse::laz {

class GpsTimeCodec {
 public:
  enum class Variant { kPointwise2, kLayered3 };
  explicit GpsTimeCodec(Variant variant);
  // Start of a chunk (or of a Point14 scanner channel context) with the previous time's bits.
  void Reset(uint64_t first);
  // Encoder: codes `time` (a double's bits) and returns it. Decoder: returns the next time.
  template <class Coder>
  uint64_t Code(Coder& coder, uint64_t time) {
    return CodeIn(coder, time, 0);
  }

 private:
  template <class Coder>
  uint64_t CodeIn(Coder& coder, uint64_t time, int depth);
  uint32_t ChooseAfterZeroDiff(uint64_t time) const;
  uint32_t ChooseMultiplier(uint64_t time) const;
  uint32_t OtherSequence(uint64_t time) const;  // 1..3 for a sequence within 32 bits of `time`, else 0
  template <class Coder>
  int32_t CodeDiff(Coder& coder, int32_t pred, uint64_t time, uint32_t context);
  template <class Coder>
  void CodeFull(Coder& coder, uint64_t time);
  void CountExtreme(int32_t diff);

  uint32_t unchanged_codes_;  // 1 for version 2 (which can say "unchanged"), 0 for version 3
  SymbolModel multiplier_;
  SymbolModel after_zero_diff_;
  IntegerCodec ic_{32, 9};
  uint32_t last_ = 0;
  uint32_t next_ = 0;
  std::array<uint64_t, 4> times_{};
  std::array<int32_t, 4> diffs_{};
  std::array<int32_t, 4> extremes_{};
};

}  // namespace sacfuse::laz
