#include "io/laz_rgb.h"

#include "io/laz_arithmetic.h"
#include "io/laz_common.h"

namespace sacfuse::laz {
namespace {

uint32_t Lo(uint16_t v) { return v & 0xFFu; }
uint32_t Hi(uint16_t v) { return v >> 8; }

uint32_t ChangeMask(const std::array<uint16_t, 3>& last, const std::array<uint16_t, 3>& rgb) {
  uint32_t mask = 0;
  for (int c = 0; c < 3; ++c) {
    if (Lo(last[c]) != Lo(rgb[c])) mask |= 1u << (2 * c);
    if (Hi(last[c]) != Hi(rgb[c])) mask |= 2u << (2 * c);
  }
  if (rgb[1] != rgb[0] || rgb[2] != rgb[0]) mask |= 64;
  return mask;
}

// One byte coded as a correction to a prediction (modulo 256).
template <class Coder>
uint32_t CodeByte(Coder& coder, SymbolModel& model, uint32_t prediction, uint32_t value) {
  return ByteSum(coder.Symbol(model, ByteDiff(value, prediction)), prediction);
}

}  // namespace

template <class Coder>
uint32_t CodeRgb(Coder& coder, RgbModels& models, std::array<uint16_t, 3>& last, std::array<uint16_t, 3>& rgb) {
  uint32_t mask = 0;
  if constexpr (Coder::kEncoding) mask = ChangeMask(last, rgb);
  mask = coder.Symbol(models.used, mask);
  // Red: plain byte differences.
  const uint32_t r_lo = (mask & 1) ? CodeByte(coder, models.diff[0], Lo(last[0]), Lo(rgb[0])) : Lo(last[0]);
  const uint32_t r_hi = (mask & 2) ? CodeByte(coder, models.diff[1], Hi(last[0]), Hi(rgb[0])) : Hi(last[0]);
  std::array<uint16_t, 3> out;
  out[0] = static_cast<uint16_t>(r_lo | (r_hi << 8));
  if (mask & 64) {
    // Green follows red's change, blue the mean of red's and green's.
    int32_t d = static_cast<int32_t>(r_lo) - static_cast<int32_t>(Lo(last[0]));
    const uint32_t g_lo = (mask & 4) ? CodeByte(coder, models.diff[2], ClampByte(d + Lo(last[1])), Lo(rgb[1]))
                                     : Lo(last[1]);
    d = (d + static_cast<int32_t>(g_lo) - static_cast<int32_t>(Lo(last[1]))) / 2;
    const uint32_t b_lo = (mask & 16) ? CodeByte(coder, models.diff[4], ClampByte(d + Lo(last[2])), Lo(rgb[2]))
                                      : Lo(last[2]);
    d = static_cast<int32_t>(r_hi) - static_cast<int32_t>(Hi(last[0]));
    const uint32_t g_hi = (mask & 8) ? CodeByte(coder, models.diff[3], ClampByte(d + Hi(last[1])), Hi(rgb[1]))
                                     : Hi(last[1]);
    d = (d + static_cast<int32_t>(g_hi) - static_cast<int32_t>(Hi(last[1]))) / 2;
    const uint32_t b_hi = (mask & 32) ? CodeByte(coder, models.diff[5], ClampByte(d + Hi(last[2])), Hi(rgb[2]))
                                      : Hi(last[2]);
    out[1] = static_cast<uint16_t>(g_lo | (g_hi << 8));
    out[2] = static_cast<uint16_t>(b_lo | (b_hi << 8));
  } else {
    out[1] = out[2] = out[0];
  }
  rgb = out;
  last = out;
  return mask;
}

template <class Coder>
uint32_t CodeNir(Coder& coder, NirModels& models, uint16_t& last, uint16_t& nir) {
  uint32_t mask = 0;
  if constexpr (Coder::kEncoding) mask = (Lo(last) != Lo(nir) ? 1u : 0u) | (Hi(last) != Hi(nir) ? 2u : 0u);
  mask = coder.Symbol(models.used, mask);
  const uint32_t lo = (mask & 1) ? CodeByte(coder, models.diff[0], Lo(last), Lo(nir)) : Lo(last);
  const uint32_t hi = (mask & 2) ? CodeByte(coder, models.diff[1], Hi(last), Hi(nir)) : Hi(last);
  nir = static_cast<uint16_t>(lo | (hi << 8));
  last = nir;
  return mask;
}

template uint32_t CodeRgb<Encoder>(Encoder&, RgbModels&, std::array<uint16_t, 3>&, std::array<uint16_t, 3>&);
template uint32_t CodeRgb<Decoder>(Decoder&, RgbModels&, std::array<uint16_t, 3>&, std::array<uint16_t, 3>&);
template uint32_t CodeNir<Encoder>(Encoder&, NirModels&, uint16_t&, uint16_t&);
template uint32_t CodeNir<Decoder>(Decoder&, NirModels&, uint16_t&, uint16_t&);

}  // namespace sacfuse::laz
