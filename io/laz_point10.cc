#include "io/laz_point10.h"

#include <cstring>

#include "io/las_format.h"

namespace sacfuse::laz {
namespace lf = las_format;

namespace {

// Bits of the changed mask.
constexpr uint32_t kReturnByteChanged = 32;
constexpr uint32_t kIntensityChanged = 16;
constexpr uint32_t kClassificationChanged = 8;
constexpr uint32_t kScanAngleChanged = 4;
constexpr uint32_t kUserDataChanged = 2;
constexpr uint32_t kPointSourceChanged = 1;

}  // namespace

Point10Codec::Point10Codec() { Reset(last_.data()); }

void Point10Codec::Reset(const uint8_t* first) {
  for (int i = 0; i < 16; ++i) {
    median_x_[i].Reset();
    median_y_[i].Reset();
  }
  last_intensity_.fill(0);
  last_z_.fill(0);
  changed_.Reset();
  return_byte_.Reset();
  classification_.Reset();
  user_data_.Reset();
  for (SymbolModel& m : scan_angle_) m.Reset();
  intensity_.Reset();
  point_source_.Reset();
  dx_.Reset();
  dy_.Reset();
  z_.Reset();
  std::memmove(last_.data(), first, kSize);
}

uint32_t Point10Codec::ChangedMask(const uint8_t* item) const {
  const uint8_t* last = last_.data();
  const uint32_t m = ReturnContext3((item[14] >> 3) & 7, item[14] & 7);
  const uint16_t intensity = lf::GetU16(item + 12);
  uint32_t mask = (last[14] != item[14] ? kReturnByteChanged : 0) |
                  (last_intensity_[m] != intensity ? kIntensityChanged : 0) |
                  (last[15] != item[15] ? kClassificationChanged : 0) |
                  (last[16] != item[16] ? kScanAngleChanged : 0) | (last[17] != item[17] ? kUserDataChanged : 0) |
                  (lf::GetU16(last + 18) != lf::GetU16(item + 18) ? kPointSourceChanged : 0);
  // With an empty mask a decoder repeats the previous point's intensity, which after the chunk's first point
  // need not be the intensity remembered for this return context: send it explicitly then.
  if (mask == 0 && intensity != lf::GetU16(last + 12)) mask = kIntensityChanged;
  return mask;
}

template <class Coder>
void Point10Codec::Code(Coder& coder, uint8_t* item) {
  uint8_t* last = last_.data();
  uint32_t changed = 0;
  if constexpr (Coder::kEncoding) changed = ChangedMask(item);
  changed = coder.Symbol(changed_, changed);

  if (changed & kReturnByteChanged) last[14] = static_cast<uint8_t>(coder.Symbol(return_byte_[last[14]], item[14]));
  const uint32_t n = (last[14] >> 3) & 7u;  // number of returns
  const uint32_t r = last[14] & 7u;         // return number
  const uint32_t m = ReturnContext3(n, r);
  const uint32_t l = ReturnLevel(n, r);
  if (changed != 0) {
    if (changed & kIntensityChanged) {
      last_intensity_[m] = static_cast<uint16_t>(
          intensity_.Code(coder, last_intensity_[m], lf::GetU16(item + 12), m < 3 ? m : 3));
    }
    lf::PutU16(last + 12, last_intensity_[m]);
    if (changed & kClassificationChanged) {
      last[15] = static_cast<uint8_t>(coder.Symbol(classification_[last[15]], item[15]));
    }
    if (changed & kScanAngleChanged) {
      const uint32_t s = coder.Symbol(scan_angle_[(last[14] >> 6) & 1], ByteDiff(item[16], last[16]));
      last[16] = ByteSum(s, last[16]);
    }
    if (changed & kUserDataChanged) last[17] = static_cast<uint8_t>(coder.Symbol(user_data_[last[17]], item[17]));
    if (changed & kPointSourceChanged) {
      lf::PutU16(last + 18, static_cast<uint16_t>(point_source_.Code(coder, lf::GetU16(last + 18),
                                                                      lf::GetU16(item + 18), 0)));
    }
  }

  const uint32_t single = n == 1 ? 1 : 0;
  const int32_t dx = dx_.Code(coder, median_x_[m].Get(), WrappingDiff(lf::GetI32(item), lf::GetI32(last)), single);
  lf::PutI32(last, WrappingSum(lf::GetI32(last), dx));
  median_x_[m].Add(dx);
  const int32_t dy = dy_.Code(coder, median_y_[m].Get(), WrappingDiff(lf::GetI32(item + 4), lf::GetI32(last + 4)),
                              single + LengthContext(dx_.k(), 20));
  lf::PutI32(last + 4, WrappingSum(lf::GetI32(last + 4), dy));
  median_y_[m].Add(dy);
  const uint32_t k_xy = (dx_.k() + dy_.k()) / 2;
  last_z_[l] = z_.Code(coder, last_z_[l], lf::GetI32(item + 8), single + LengthContext(k_xy, 18));
  lf::PutI32(last + 8, last_z_[l]);

  std::memcpy(item, last, kSize);
}

template void Point10Codec::Code<Encoder>(Encoder&, uint8_t*);
template void Point10Codec::Code<Decoder>(Decoder&, uint8_t*);

}  // namespace sacfuse::laz
