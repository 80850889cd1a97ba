#include "io/laz_models.h"

#include <stdexcept>

namespace sacfuse::laz {
namespace {

constexpr uint32_t kBitCountLimit = 1u << BitModel::kProbabilityBits;     // counts halved beyond this
constexpr uint32_t kSymbolCountLimit = 1u << SymbolModel::kDistributionBits;
constexpr uint32_t kMaxBitUpdateCycle = 64;

}  // namespace

void BitModel::Reset() {
  zero_count_ = 1;
  total_count_ = 2;
  zero_probability_ = 1u << (kProbabilityBits - 1);
  update_cycle_ = until_update_ = 4;  // frequent updates while the model is young
}

void BitModel::Update() {
  total_count_ += update_cycle_;
  if (total_count_ > kBitCountLimit) {
    total_count_ = (total_count_ + 1) >> 1;
    zero_count_ = (zero_count_ + 1) >> 1;
    if (zero_count_ == total_count_) ++total_count_;
  }
  const uint32_t scale = 0x80000000u / total_count_;
  zero_probability_ = (zero_count_ * scale) >> (31 - kProbabilityBits);
  update_cycle_ = (5 * update_cycle_) >> 2;
  if (update_cycle_ > kMaxBitUpdateCycle) update_cycle_ = kMaxBitUpdateCycle;
  until_update_ = update_cycle_;
}

SymbolModel::SymbolModel(uint32_t symbols) {
  if (symbols < 2 || symbols > 2048) throw std::invalid_argument("LAZ symbol model needs 2..2048 symbols");
  counts_.resize(symbols);
  cumulative_.resize(symbols);
  if (symbols > 16) {
    uint32_t bits = 3;
    while (symbols > (1u << (bits + 2))) ++bits;
    lookup_.resize((size_t{1} << bits) + 2);
    lookup_shift_ = kDistributionBits - bits;
  }
  Reset();
}

void SymbolModel::Reset() {
  const uint32_t n = symbols();
  for (uint32_t& c : counts_) c = 1;
  total_count_ = 0;
  update_cycle_ = n;
  Update();
  update_cycle_ = until_update_ = (n + 6) >> 1;
}

void SymbolModel::Update() {
  const uint32_t n = symbols();
  total_count_ += update_cycle_;
  if (total_count_ > kSymbolCountLimit) {
    total_count_ = 0;
    for (uint32_t& c : counts_) {
      c = (c + 1) >> 1;
      total_count_ += c;
    }
  }
  const uint32_t scale = 0x80000000u / total_count_;
  uint32_t sum = 0;
  for (uint32_t k = 0; k < n; ++k) {
    cumulative_[k] = (scale * sum) >> (31 - kDistributionBits);
    sum += counts_[k];
  }
  if (!lookup_.empty()) {
    // lookup_[i]: the last symbol whose cumulative value is below i << shift.
    const uint32_t slots = static_cast<uint32_t>(lookup_.size()) - 2;
    uint32_t slot = 0;
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t reach = cumulative_[k] >> lookup_shift_;
      while (slot < reach) lookup_[++slot] = k - 1;
    }
    lookup_[0] = 0;
    while (slot <= slots) lookup_[++slot] = n - 1;
  }
  update_cycle_ = (5 * update_cycle_) >> 2;
  const uint32_t max_cycle = (n + 6) << 3;
  if (update_cycle_ > max_cycle) update_cycle_ = max_cycle;
  until_update_ = update_cycle_;
}

}  // namespace sacfuse::laz
