#include "io/laz_integer.h"

#include <algorithm>
#include <limits>

namespace sacfuse::laz {

IntegerCodec::IntegerCodec(uint32_t bits, uint32_t contexts) {
  if (bits >= 1 && bits < 32) {
    corr_bits_ = bits;
    corr_range_ = 1u << bits;
    corr_min_ = -static_cast<int32_t>(corr_range_ / 2);
    corr_max_ = static_cast<int32_t>(corr_min_ + corr_range_ - 1);
  } else {
    corr_bits_ = 32;
    corr_range_ = 0;
    corr_min_ = std::numeric_limits<int32_t>::min();
    corr_max_ = std::numeric_limits<int32_t>::max();
  }
  for (uint32_t c = 0; c < contexts; ++c) k_models_.emplace_back(corr_bits_ + 1);
  classes_.resize(corr_bits_ + 1);
  for (uint32_t k = 1; k <= corr_bits_; ++k) {
    classes_[k] = std::make_unique<SymbolModel>(1u << std::min(k, kHighBits));
  }
}

void IntegerCodec::Reset() {
  for (SymbolModel& m : k_models_) m.Reset();
  zero_or_one_.Reset();
  for (uint32_t k = 1; k <= corr_bits_; ++k) classes_[k]->Reset();
  k_ = 0;
}

void IntegerCodec::Encode(Encoder& encoder, int32_t pred, int32_t real, uint32_t context) {
  // Wrapping difference, folded into [corr_min, corr_max].
  int64_t corr = static_cast<int32_t>(static_cast<uint32_t>(real) - static_cast<uint32_t>(pred));
  if (corr_range_ != 0) {
    if (corr < corr_min_) {
      corr += corr_range_;
    } else if (corr > corr_max_) {
      corr -= corr_range_;
    }
  }
  // Length class: k bits hold |c| - (c > 0): class k holds [-(2^k - 1), -2^(k-1)] and [2^(k-1) + 1, 2^k].
  uint64_t magnitude = corr <= 0 ? static_cast<uint64_t>(-corr) : static_cast<uint64_t>(corr - 1);
  uint32_t k = 0;
  while (magnitude != 0) {
    magnitude >>= 1;
    ++k;
  }
  k_ = k;
  encoder.Symbol(k_models_[context], k);
  if (k == 0) {
    encoder.Bit(zero_or_one_, static_cast<uint32_t>(corr));
    return;
  }
  if (k >= 32) return;  // only the minimum corrector has this class; the class says it all
  // Position within the class: negatives map to [0, 2^(k-1) - 1], positives to [2^(k-1), 2^k - 1].
  const uint32_t offset = static_cast<uint32_t>(corr < 0 ? corr + ((int64_t{1} << k) - 1) : corr - 1);
  if (k <= kHighBits) {
    encoder.Symbol(*classes_[k], offset);
  } else {
    const uint32_t low_bits = k - kHighBits;
    encoder.Symbol(*classes_[k], offset >> low_bits);
    encoder.Bits(low_bits, offset & ((1u << low_bits) - 1));
  }
}

int32_t IntegerCodec::Decode(Decoder& decoder, int32_t pred, uint32_t context) {
  const uint32_t k = decoder.Symbol(k_models_[context]);
  k_ = k;
  int64_t corr = 0;
  if (k == 0) {
    corr = decoder.Bit(zero_or_one_);
  } else if (k >= 32) {
    corr = corr_min_;
  } else {
    uint32_t offset = 0;
    if (k <= kHighBits) {
      offset = decoder.Symbol(*classes_[k]);
    } else {
      const uint32_t low_bits = k - kHighBits;
      offset = decoder.Symbol(*classes_[k]) << low_bits;
      offset |= decoder.Bits(low_bits);
    }
    if (offset >= (1u << (k - 1))) {
      corr = static_cast<int64_t>(offset) + 1;
    } else {
      corr = static_cast<int64_t>(offset) - ((int64_t{1} << k) - 1);
    }
  }
  // Wrap back into the value range.
  int32_t real = static_cast<int32_t>(static_cast<uint32_t>(pred) + static_cast<uint32_t>(corr));
  if (corr_range_ != 0) {
    if (real < 0) {
      real = static_cast<int32_t>(static_cast<uint32_t>(real) + corr_range_);
    } else if (static_cast<uint32_t>(real) >= corr_range_) {
      real = static_cast<int32_t>(static_cast<uint32_t>(real) - corr_range_);
    }
  }
  return real;
}

}  // namespace sacfuse::laz
