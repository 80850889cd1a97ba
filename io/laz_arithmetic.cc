#include "io/laz_arithmetic.h"

#include <algorithm>

namespace sacfuse::laz {
namespace {

constexpr uint32_t kMaxLength = 0xFFFFFFFFu;
// Bits above which Bits() sends the low 16 bits first (the coder's 32-bit product leaves room for 19).
constexpr uint32_t kMaxDirectBits = 19;
// A valid stream is self-contained (the encoder's closing bytes cover the decoder's look-ahead); a few zero bytes
// past the end are tolerated like the reference decoder's zero-filled buffers, more mean the data are corrupt.
constexpr size_t kMaxOverrun = 8;

}  // namespace

// ---------------------------------------------------------------------------------------------------- Encoder

void Encoder::Start(std::vector<uint8_t>* out) {
  out_ = out;
  start_ = out->size();
  base_ = 0;
  length_ = kMaxLength;
}

void Encoder::PropagateCarry() {
  // The new base wrapped around: add one to the bytes already written, rippling through 0xFF bytes.
  size_t i = out_->size();
  while (i > start_) {
    --i;
    if ((*out_)[i] != 0xFF) {
      ++(*out_)[i];
      return;
    }
    (*out_)[i] = 0;
  }
}

void Encoder::Renormalise() {
  do {
    out_->push_back(static_cast<uint8_t>(base_ >> 24));
    base_ <<= 8;
  } while ((length_ <<= 8) < kMinLength);
}

uint32_t Encoder::Bit(BitModel& model, uint32_t bit) {
  const uint32_t x = model.zero_probability() * (length_ >> BitModel::kProbabilityBits);
  const uint32_t old_base = base_;
  if (bit == 0) {
    length_ = x;
  } else {
    base_ += x;
    length_ -= x;
  }
  AfterBaseChange(old_base);
  model.Count(bit);
  return bit;
}

uint32_t Encoder::Symbol(SymbolModel& model, uint32_t symbol) {
  const uint32_t old_base = base_;
  if (symbol + 1 == model.symbols()) {  // the last symbol takes the rest of the interval
    const uint32_t x = model.cumulative(symbol) * (length_ >> SymbolModel::kDistributionBits);
    base_ += x;
    length_ -= x;
  } else {
    length_ >>= SymbolModel::kDistributionBits;
    const uint32_t x = model.cumulative(symbol) * length_;
    base_ += x;
    length_ = model.cumulative(symbol + 1) * length_ - x;
  }
  AfterBaseChange(old_base);
  model.Count(symbol);
  return symbol;
}

void Encoder::ShiftIn(uint32_t bits, uint32_t value) {
  const uint32_t old_base = base_;
  length_ >>= bits;
  base_ += value * length_;
  AfterBaseChange(old_base);
}

uint32_t Encoder::Bits(uint32_t bits, uint32_t value) {
  const uint32_t all = value;
  if (bits > kMaxDirectBits) {
    ShiftIn(16, value & 0xFFFFu);
    value >>= 16;
    bits -= 16;
  }
  ShiftIn(bits, value);
  return all;
}

void Encoder::Finish() {
  // Choose a final value inside the interval that needs as few bytes as possible, then pad with zeros so that
  // the decoder's 4-byte window never reads past the stream.
  const uint32_t old_base = base_;
  bool one_more_zero = true;
  if (length_ > 2 * kMinLength) {
    base_ += kMinLength;
    length_ = kMinLength >> 1;
  } else {
    base_ += kMinLength >> 1;
    length_ = kMinLength >> 9;
    one_more_zero = false;
  }
  if (base_ < old_base) PropagateCarry();
  Renormalise();
  out_->push_back(0);
  out_->push_back(0);
  if (one_more_zero) out_->push_back(0);
  out_ = nullptr;
}

// ---------------------------------------------------------------------------------------------------- Decoder

void Decoder::Start(const uint8_t* data, size_t size) {
  next_ = data;
  end_ = data + size;
  overrun_ = 0;
  length_ = kMaxLength;
  value_ = 0;
  for (int i = 0; i < 4; ++i) value_ = (value_ << 8) | NextByte();
}

uint8_t Decoder::NextByte() {
  if (next_ < end_) return *next_++;
  if (++overrun_ > kMaxOverrun) throw DataError("compressed stream ends early (truncated or corrupt data)");
  return 0;
}

void Decoder::Renormalise() {
  if (length_ == 0) throw DataError("arithmetic decoder interval collapsed (corrupt data)");
  do {
    value_ = (value_ << 8) | NextByte();
  } while ((length_ <<= 8) < kMinLength);
}

uint32_t Decoder::Bit(BitModel& model, uint32_t) {
  const uint32_t x = model.zero_probability() * (length_ >> BitModel::kProbabilityBits);
  const uint32_t bit = value_ >= x ? 1 : 0;
  if (bit == 0) {
    length_ = x;
  } else {
    value_ -= x;
    length_ -= x;
  }
  if (length_ < kMinLength) Renormalise();
  model.Count(bit);
  return bit;
}

uint32_t Decoder::Symbol(SymbolModel& model, uint32_t) {
  if (!model.lookup().empty()) return LookupSymbol(model);
  // Bisection for the last symbol whose interval start is <= value.
  uint32_t upper_length = length_;  // end of the interval of the last symbol
  length_ >>= SymbolModel::kDistributionBits;
  uint32_t symbol = 0;
  uint32_t low = 0;
  uint32_t n = model.symbols();
  uint32_t k = n >> 1;
  do {
    const uint32_t z = length_ * model.cumulative(k);
    if (z > value_) {
      n = k;
      upper_length = z;
    } else {
      symbol = k;
      low = z;
    }
  } while ((k = (symbol + n) >> 1) != symbol);
  value_ -= low;
  length_ = upper_length - low;
  if (length_ < kMinLength) Renormalise();
  model.Count(symbol);
  return symbol;
}

uint32_t Decoder::LookupSymbol(SymbolModel& model) {
  // Same result as the bisection over all symbols, started from the model's lookup table.
  const uint32_t full_length = length_;
  length_ >>= SymbolModel::kDistributionBits;
  const uint32_t target = value_ / length_;
  const std::vector<uint32_t>& lookup = model.lookup();
  // Corrupt data can put the value beyond the interval: clamp into the table.
  const uint32_t slot = std::min<uint32_t>(target >> model.lookup_shift(), static_cast<uint32_t>(lookup.size()) - 2);
  uint32_t symbol = lookup[slot];
  uint32_t n = lookup[slot + 1] + 1;
  while (n > symbol + 1) {
    const uint32_t k = (symbol + n) >> 1;
    if (model.cumulative(k) > target) {
      n = k;
    } else {
      symbol = k;
    }
  }
  const uint32_t low = model.cumulative(symbol) * length_;
  const uint32_t high = symbol + 1 == model.symbols() ? full_length : model.cumulative(symbol + 1) * length_;
  value_ -= low;
  length_ = high - low;
  if (length_ < kMinLength) Renormalise();
  model.Count(symbol);
  return symbol;
}

uint32_t Decoder::ShiftOut(uint32_t bits) {
  length_ >>= bits;
  const uint32_t value = value_ / length_;
  value_ -= length_ * value;
  if (length_ < kMinLength) Renormalise();
  if (value >= (1u << bits)) throw DataError("raw bits out of range (corrupt data)");
  return value;
}

uint32_t Decoder::Bits(uint32_t bits, uint32_t) {
  if (bits > kMaxDirectBits) {
    const uint32_t low = ShiftOut(16);
    return (ShiftOut(bits - 16) << 16) | low;
  }
  return ShiftOut(bits);
}

}  // namespace sacfuse::laz
