#pragma once
// The LASzip range coder (LASzip compressed data format: 32-bit base and length, renormalisation by bytes when the
// length falls below 2^24, carries propagated back into the bytes already written, and a closing sequence that
// leaves the decoder's 4-byte look-ahead inside the stream). Private to io/laz_*.
//
// Encoder and decoder share one calling convention so that every item codec is written once for both
// directions: Symbol(model, s) / Bit(model, b) / Bits(n, v) code `s` when encoding and return it, and ignore their
// value argument and return what was decoded when decoding (`kEncoding` tells the codec which one it runs).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/laz_models.h"

namespace sacfuse::laz {

// Corrupt or truncated compressed data; the LAS reader turns it into an InputError naming the file and chunk.
class DataError : public std::runtime_error {
 public:
  explicit DataError(const std::string& message) : std::runtime_error(message) {}
};

class Encoder {
 public:
  static constexpr bool kEncoding = true;

  // Starts a new stream appended to *out (which must outlive the encoder's use until Finish()).
  void Start(std::vector<uint8_t>* out);
  // Writes the closing bytes; the stream is then complete.
  void Finish();

  uint32_t Symbol(SymbolModel& model, uint32_t symbol);
  uint32_t Bit(BitModel& model, uint32_t bit);
  // `bits` (1..32) raw bits, without a model.
  uint32_t Bits(uint32_t bits, uint32_t value);

 private:
  void ShiftIn(uint32_t bits, uint32_t value);  // bits <= 16
  void AfterBaseChange(uint32_t old_base) {
    if (base_ < old_base) PropagateCarry();
    if (length_ < kMinLength) Renormalise();
  }
  void PropagateCarry();
  void Renormalise();

  static constexpr uint32_t kMinLength = 1u << 24;
  std::vector<uint8_t>* out_ = nullptr;
  size_t start_ = 0;  // where this stream begins in *out_ (carries never cross it)
  uint32_t base_ = 0;
  uint32_t length_ = 0;
};

class Decoder {
 public:
  static constexpr bool kEncoding = false;

  // Starts decoding the stream in [data, data + size); the bytes must outlive the decoder's use.
  void Start(const uint8_t* data, size_t size);

  uint32_t Symbol(SymbolModel& model, uint32_t ignored = 0);
  uint32_t Bit(BitModel& model, uint32_t ignored = 0);
  uint32_t Bits(uint32_t bits, uint32_t ignored = 0);

 private:
  uint32_t ShiftOut(uint32_t bits);  // bits <= 16
  uint32_t LookupSymbol(SymbolModel& model);
  uint8_t NextByte();
  void Renormalise();

  static constexpr uint32_t kMinLength = 1u << 24;
  const uint8_t* next_ = nullptr;
  const uint8_t* end_ = nullptr;
  size_t overrun_ = 0;  // zero bytes supplied past the end (a valid stream needs none)
  uint32_t value_ = 0;
  uint32_t length_ = 0;
};

}  // namespace sacfuse::laz
