#pragma once
// The LASzip integer compressor (LASzip compressed data format, "integer compressor"): an integer is coded as
// its difference ("corrector") to a prediction. The corrector's bit length k is coded with a per-context symbol
// model; for k <= 8 the corrector within its length class is coded with a model of that class, for larger k the
// top 8 bits get the model and the low k - 8 bits are sent raw. Correctors are wrapped into the value range of
// `bits`-bit integers. Private to io/laz_*.
#include <cstdint>
#include <memory>
#include <vector>

#include "io/laz_arithmetic.h"
#include "io/laz_models.h"

namespace sacfuse::laz {

class IntegerCodec {
 public:
  // bits: width of the values (1..32); contexts: number of separately modelled contexts.
  explicit IntegerCodec(uint32_t bits = 16, uint32_t contexts = 1);
  // Fresh models (start of a chunk).
  void Reset();

  // Encoding: codes `real` predicted by `pred` and returns it. Decoding: returns the decoded value.
  template <class Coder>
  int32_t Code(Coder& coder, int32_t pred, int32_t real, uint32_t context) {
    if constexpr (Coder::kEncoding) {
      Encode(coder, pred, real, context);
      return real;
    } else {
      return Decode(coder, pred, context);
    }
  }
  // Bit length class of the last corrector coded (used as context by the point codecs).
  uint32_t k() const { return k_; }

 private:
  void Encode(Encoder& encoder, int32_t pred, int32_t real, uint32_t context);
  int32_t Decode(Decoder& decoder, int32_t pred, uint32_t context);

  static constexpr uint32_t kHighBits = 8;  // length classes above this send their low bits raw
  uint32_t corr_bits_ = 32;
  uint32_t corr_range_ = 0;  // 0: the full 32-bit range
  int32_t corr_min_ = 0;
  int32_t corr_max_ = 0;
  uint32_t k_ = 0;
  std::vector<SymbolModel> k_models_;                  // per context: the corrector's bit length
  BitModel zero_or_one_;                                // corrector of length class 0: 0 or 1
  std::vector<std::unique_ptr<SymbolModel>> classes_;  // [k]: corrector within length class k (1..corr_bits)
};

}  // namespace sacfuse::laz
