#pragma once
// Adaptive probability models of the LASzip entropy coder (LASzip compressed data format, "arithmetic coder"
// section: the range coder of A. Said's FastAC with periodic model updates). Private to io/laz_*.
//
// Both models count the symbols coded and recompute their probabilities only every `update_cycle` symbols; the
// cycle grows by 5/4 after each update up to a cap, and counts are halved when their total passes a threshold.
// Encoder and decoder run the same updates in the same order, so the probabilities never need transmitting.
#include <cstdint>
#include <vector>

namespace sacfuse::laz {

// Binary model: probability of a 0 bit, in units of 2^-13.
class BitModel {
 public:
  static constexpr uint32_t kProbabilityBits = 13;

  BitModel() { Reset(); }
  // Back to the equiprobable state of a new chunk.
  void Reset();
  // Called by the coder after each bit: counts it, and recomputes the probability when a cycle ends.
  void Count(uint32_t bit) {
    if (bit == 0) ++zero_count_;
    if (--until_update_ == 0) Update();
  }
  uint32_t zero_probability() const { return zero_probability_; }

 private:
  void Update();
  uint32_t update_cycle_ = 0;
  uint32_t until_update_ = 0;
  uint32_t zero_probability_ = 0;
  uint32_t zero_count_ = 0;
  uint32_t total_count_ = 0;
};

// Model of an alphabet of 2..2048 symbols: cumulative distribution in units of 2^-15.
class SymbolModel {
 public:
  static constexpr uint32_t kDistributionBits = 15;

  explicit SymbolModel(uint32_t symbols);
  void Reset();
  void Count(uint32_t symbol) {
    ++counts_[symbol];
    if (--until_update_ == 0) Update();
  }
  uint32_t symbols() const { return static_cast<uint32_t>(counts_.size()); }
  // Cumulative probability of the symbols before `symbol` (symbol < symbols()).
  uint32_t cumulative(uint32_t symbol) const { return cumulative_[symbol]; }
  // Decoding speed-up for alphabets of more than 16 symbols (else empty): for a cumulative value v,
  // lookup()[v >> lookup_shift()] is a symbol at or before v's and lookup()[that index + 1] + 1 one after it.
  const std::vector<uint32_t>& lookup() const { return lookup_; }
  uint32_t lookup_shift() const { return lookup_shift_; }

 private:
  void Update();
  std::vector<uint32_t> counts_;
  std::vector<uint32_t> cumulative_;
  std::vector<uint32_t> lookup_;
  uint32_t lookup_shift_ = 0;
  uint32_t total_count_ = 0;
  uint32_t update_cycle_ = 0;
  uint32_t until_update_ = 0;
};

}  // namespace sacfuse::laz
