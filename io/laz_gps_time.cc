#include "io/laz_gps_time.h"

#include <cmath>

namespace sacfuse::laz {
namespace {

constexpr int32_t kMaxMultiplier = 500;   // multipliers 1..499 coded directly, 500 stands for "larger"
constexpr int32_t kMinMultiplier = -10;   // -1..-9 coded directly, -10 stands for "smaller"
constexpr uint32_t kMultiplierCodes = kMaxMultiplier - kMinMultiplier + 1;  // 0..510: multiplier codes
constexpr int kMaxExtremes = 3;  // after more extreme multipliers in a row, the reference difference follows

bool Fits32(uint64_t a, uint64_t b, int32_t* diff) {
  const int64_t d = static_cast<int64_t>(a - b);
  *diff = static_cast<int32_t>(d);
  return d == static_cast<int64_t>(*diff);
}

int32_t WrappingProduct(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) * static_cast<uint32_t>(b));
}

}  // namespace

GpsTimeCodec::GpsTimeCodec(Variant variant)
    : unchanged_codes_(variant == Variant::kPointwise2 ? 1 : 0),
      multiplier_(kMultiplierCodes + unchanged_codes_ + 4),
      after_zero_diff_(unchanged_codes_ + 5) {}

void GpsTimeCodec::Reset(uint64_t first) {
  multiplier_.Reset();
  after_zero_diff_.Reset();
  ic_.Reset();
  last_ = next_ = 0;
  times_ = {first, 0, 0, 0};
  diffs_.fill(0);
  extremes_.fill(0);
}

uint32_t GpsTimeCodec::OtherSequence(uint64_t time) const {
  int32_t d = 0;
  for (uint32_t i = 1; i < 4; ++i) {
    if (Fits32(time, times_[(last_ + i) & 3], &d)) return i;
  }
  return 0;
}

// Symbols when the last difference was 0: [unchanged], 32-bit difference, full time, other sequence 1..3.
uint32_t GpsTimeCodec::ChooseAfterZeroDiff(uint64_t time) const {
  const uint32_t u = unchanged_codes_;
  if (u != 0 && time == times_[last_]) return 0;
  int32_t d = 0;
  if (Fits32(time, times_[last_], &d)) return u;
  const uint32_t other = OtherSequence(time);
  return other != 0 ? u + 1 + other : u + 1;
}

// Symbols otherwise: 0..510 multiplier codes, [unchanged], full time, other sequence 1..3.
uint32_t GpsTimeCodec::ChooseMultiplier(uint64_t time) const {
  const uint32_t u = unchanged_codes_;
  if (u != 0 && time == times_[last_]) return kMultiplierCodes;
  int32_t d = 0;
  if (!Fits32(time, times_[last_], &d)) {
    const uint32_t other = OtherSequence(time);
    return kMultiplierCodes + u + other;
  }
  const double ratio = static_cast<double>(static_cast<float>(d) / static_cast<float>(diffs_[last_]));
  const double rounded = ratio >= 0 ? std::floor(ratio + 0.5) : std::ceil(ratio - 0.5);
  if (rounded >= kMaxMultiplier) return kMaxMultiplier;
  if (rounded <= kMinMultiplier) return kMaxMultiplier - kMinMultiplier;
  const int32_t multi = static_cast<int32_t>(rounded);
  if (multi >= 0) return static_cast<uint32_t>(multi);
  return static_cast<uint32_t>(kMaxMultiplier - multi);
}

template <class Coder>
int32_t GpsTimeCodec::CodeDiff(Coder& coder, int32_t pred, uint64_t time, uint32_t context) {
  int32_t d = 0;
  Fits32(time, times_[last_], &d);
  return ic_.Code(coder, pred, d, context);
}

template <class Coder>
void GpsTimeCodec::CodeFull(Coder& coder, uint64_t time) {
  const int32_t high = ic_.Code(coder, static_cast<int32_t>(times_[last_] >> 32), static_cast<int32_t>(time >> 32), 8);
  const uint32_t low = coder.Bits(32, static_cast<uint32_t>(time));
  next_ = (next_ + 1) & 3;
  last_ = next_;
  times_[last_] = (static_cast<uint64_t>(static_cast<uint32_t>(high)) << 32) | low;
  diffs_[last_] = 0;
  extremes_[last_] = 0;
}

void GpsTimeCodec::CountExtreme(int32_t diff) {
  if (++extremes_[last_] > kMaxExtremes) {
    diffs_[last_] = diff;
    extremes_[last_] = 0;
  }
}

template <class Coder>
uint64_t GpsTimeCodec::CodeIn(Coder& coder, uint64_t time, int depth) {
  if (depth > 1) throw DataError("GPS time switches sequence twice (corrupt data)");
  const uint32_t u = unchanged_codes_;
  if (diffs_[last_] == 0) {
    uint32_t sym = 0;
    if constexpr (Coder::kEncoding) sym = ChooseAfterZeroDiff(time);
    sym = coder.Symbol(after_zero_diff_, sym);
    if (u != 0 && sym == 0) return times_[last_];
    if (sym == u) {
      const int32_t d = CodeDiff(coder, 0, time, 0);
      times_[last_] += static_cast<uint64_t>(static_cast<int64_t>(d));
      diffs_[last_] = d;
      extremes_[last_] = 0;
    } else if (sym == u + 1) {
      CodeFull(coder, time);
    } else {
      last_ = (last_ + sym - (u + 1)) & 3;
      return CodeIn(coder, time, depth + 1);
    }
    return times_[last_];
  }

  uint32_t sym = 0;
  if constexpr (Coder::kEncoding) sym = ChooseMultiplier(time);
  sym = coder.Symbol(multiplier_, sym);
  if (sym < kMultiplierCodes) {
    const int32_t ref = diffs_[last_];
    int32_t d = 0;
    if (sym == 1) {
      d = CodeDiff(coder, ref, time, 1);
      extremes_[last_] = 0;
    } else if (sym == 0) {
      d = CodeDiff(coder, 0, time, 7);
      CountExtreme(d);
    } else if (sym < static_cast<uint32_t>(kMaxMultiplier)) {
      d = CodeDiff(coder, WrappingProduct(static_cast<int32_t>(sym), ref), time, sym < 10 ? 2 : 3);
    } else if (sym == static_cast<uint32_t>(kMaxMultiplier)) {
      d = CodeDiff(coder, WrappingProduct(kMaxMultiplier, ref), time, 4);
      CountExtreme(d);
    } else {
      const int32_t multi = kMaxMultiplier - static_cast<int32_t>(sym);  // -1..-10
      if (multi > kMinMultiplier) {
        d = CodeDiff(coder, WrappingProduct(multi, ref), time, 5);
      } else {
        d = CodeDiff(coder, WrappingProduct(kMinMultiplier, ref), time, 6);
        CountExtreme(d);
      }
    }
    times_[last_] += static_cast<uint64_t>(static_cast<int64_t>(d));
    return times_[last_];
  }
  if (u != 0 && sym == kMultiplierCodes) return times_[last_];
  if (sym == kMultiplierCodes + u) {
    CodeFull(coder, time);
    return times_[last_];
  }
  last_ = (last_ + sym - (kMultiplierCodes + u)) & 3;
  return CodeIn(coder, time, depth + 1);
}

template uint64_t GpsTimeCodec::CodeIn<Encoder>(Encoder&, uint64_t, int);
template uint64_t GpsTimeCodec::CodeIn<Decoder>(Decoder&, uint64_t, int);

}  // namespace sacfuse::laz
