#pragma once
// Small pieces shared by the LAZ point codecs (LASzip compressed data format, "Point10 v2" and "Point14 v3"
// sections): the streaming median of the last five coordinate differences, the context tables that group
// (return number, number of returns) pairs, lazily created models, and byte folding. Private to io/laz_*.
#include <array>
#include <cstdint>
#include <memory>

#include "io/laz_models.h"

namespace sacfuse::laz {

// Median of the last five values added (starts at five zeros). Each Add() replaces the smallest or the largest
// value kept, alternating with the side the new value falls on, as the format prescribes.
class Median5 {
 public:
  void Reset() {
    values_ = {0, 0, 0, 0, 0};
    replace_high_ = true;
  }
  int32_t Get() const { return values_[2]; }
  void Add(int32_t v);

 private:
  std::array<int32_t, 5> values_ = {0, 0, 0, 0, 0};
  bool replace_high_ = true;
};

// Context of (number of returns n, return number r) for Point10 (3-bit fields): 16 classes.
uint32_t ReturnContext3(uint32_t n, uint32_t r);
// Context of (n, r) for Point14 (4-bit fields): 6 classes.
uint32_t ReturnContext4(uint32_t n, uint32_t r);
// "Penetration level" |n - r|: up to 7 for Point10; capped at 7 for Point14.
inline uint32_t ReturnLevel(uint32_t n, uint32_t r) {
  const uint32_t d = n > r ? n - r : r - n;
  return d < 7 ? d : 7;
}

// Context of the Y and Z corrector models from the X (and Y) corrector length classes k: even classes below a cap.
inline uint32_t LengthContext(uint32_t k, uint32_t cap) { return k < cap ? (k & ~1u) : cap; }

// Coordinate differences and sums modulo 2^32 (the integer compressor codes them wrapped).
inline int32_t WrappingDiff(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) - static_cast<uint32_t>(b));
}
inline int32_t WrappingSum(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) + static_cast<uint32_t>(b));
}

// Byte difference and sum modulo 256 (the "fold" of the format).
inline uint8_t ByteDiff(uint32_t value, uint32_t last) { return static_cast<uint8_t>(value - last); }
inline uint8_t ByteSum(uint32_t symbol, uint32_t last) { return static_cast<uint8_t>(symbol + last); }
inline uint32_t ClampByte(int32_t v) { return v <= 0 ? 0u : (v >= 255 ? 255u : static_cast<uint32_t>(v)); }

// Models indexed by a previous value, created on first use and reset at the start of each chunk.
template <size_t N>
class LazyModels {
 public:
  explicit LazyModels(uint32_t symbols) : symbols_(symbols) {}
  SymbolModel& operator[](size_t i) {
    if (!models_[i]) models_[i] = std::make_unique<SymbolModel>(symbols_);
    return *models_[i];
  }
  void Reset() {
    for (auto& m : models_) {
      if (m) m->Reset();
    }
  }

 private:
  uint32_t symbols_;
  std::array<std::unique_ptr<SymbolModel>, N> models_;
};

}  // namespace sacfuse::laz
