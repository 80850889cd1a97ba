#include "io/laz_point14.h"

#include "io/las_format.h"

namespace sacfuse::laz {
namespace lf = las_format;

namespace {

// Bits of the changed mask (returns + XY layer).
constexpr uint32_t kChannelChanged = 64;
constexpr uint32_t kPointSourceChanged = 32;
constexpr uint32_t kGpsTimeChanged = 16;
constexpr uint32_t kScanAngleChanged = 8;
constexpr uint32_t kNumberOfReturnsChanged = 4;
constexpr uint32_t kReturnNumberMask = 3;  // 0 same, 1 plus one, 2 minus one, 3 coded

}  // namespace

Point14Fields Point14Fields::FromRecord(const uint8_t* p) {
  Point14Fields f;
  f.x = lf::GetI32(p);
  f.y = lf::GetI32(p + 4);
  f.z = lf::GetI32(p + 8);
  f.intensity = lf::GetU16(p + 12);
  f.return_number = p[14] & 15u;
  f.number_of_returns = p[14] >> 4;
  f.class_flags = p[15] & 15u;
  f.scanner_channel = (p[15] >> 4) & 3u;
  f.scan_direction = (p[15] >> 6) & 1u;
  f.edge = p[15] >> 7;
  f.classification = p[16];
  f.user_data = p[17];
  f.scan_angle = static_cast<int16_t>(lf::GetU16(p + 18));
  f.point_source = lf::GetU16(p + 20);
  f.gps_time = lf::GetU64(p + 22);
  return f;
}

void Point14Fields::ToRecord(uint8_t* p) const {
  lf::PutI32(p, x);
  lf::PutI32(p + 4, y);
  lf::PutI32(p + 8, z);
  lf::PutU16(p + 12, intensity);
  p[14] = static_cast<uint8_t>(return_number | (number_of_returns << 4));
  p[15] = static_cast<uint8_t>(class_flags | (scanner_channel << 4) | (scan_direction << 6) | (edge << 7));
  p[16] = static_cast<uint8_t>(classification);
  p[17] = static_cast<uint8_t>(user_data);
  lf::PutU16(p + 18, static_cast<uint16_t>(scan_angle));
  lf::PutU16(p + 20, point_source);
  lf::PutU64(p + 22, gps_time);
}

// Everything one scanner channel remembers: its previous point and its models.
struct Point14Codec::Context {
  bool unused = true;
  Point14Fields last;
  std::array<uint16_t, 8> last_intensity{};
  std::array<Median5, 12> median_x;
  std::array<Median5, 12> median_y;
  std::array<int32_t, 8> last_z{};

  std::array<SymbolModel, 8> changed_values{SymbolModel(128), SymbolModel(128), SymbolModel(128), SymbolModel(128),
                                            SymbolModel(128), SymbolModel(128), SymbolModel(128), SymbolModel(128)};
  SymbolModel channel_step{3};
  LazyModels<16> number_of_returns{16};
  LazyModels<16> return_number{16};
  SymbolModel return_step_same_time{13};
  IntegerCodec dx{32, 2};
  IntegerCodec dy{32, 22};
  IntegerCodec z{32, 20};
  LazyModels<64> classification{256};
  LazyModels<64> flags{64};
  LazyModels<64> user_data{256};
  IntegerCodec intensity{16, 4};
  IntegerCodec scan_angle{16, 2};
  IntegerCodec point_source{16, 1};
  GpsTimeCodec gps{GpsTimeCodec::Variant::kLayered3};

  void Reset(const Point14Fields& from) {
    for (SymbolModel& m : changed_values) m.Reset();
    channel_step.Reset();
    number_of_returns.Reset();
    return_number.Reset();
    return_step_same_time.Reset();
    dx.Reset();
    dy.Reset();
    z.Reset();
    classification.Reset();
    flags.Reset();
    user_data.Reset();
    intensity.Reset();
    scan_angle.Reset();
    point_source.Reset();
    gps.Reset(from.gps_time);
    for (Median5& m : median_x) m.Reset();
    for (Median5& m : median_y) m.Reset();
    last_z.fill(from.z);
    last_intensity.fill(from.intensity);
    last = from;
    last.gps_time_changed = false;
    unused = false;
  }
};

Point14Codec::Point14Codec() {
  for (auto& c : contexts_) c = std::make_unique<Context>();
}

Point14Codec::~Point14Codec() = default;

void Point14Codec::InitContext(uint32_t channel, const Point14Fields& from) {
  const Point14Fields copy = from;  // `from` may be another context's state
  contexts_[channel]->Reset(copy);
}

void Point14Codec::Reset(const uint8_t* first, const std::array<bool, kPoint14Layers>& present) {
  for (auto& c : contexts_) c->unused = true;
  const Point14Fields f = Point14Fields::FromRecord(first);
  current_ = f.scanner_channel;
  item_context_ = current_;
  InitContext(current_, f);
  present_ = present;
  changed_.fill(false);
  changed_[kLayerReturnsXY] = changed_[kLayerZ] = true;  // always stored
}

template <class Coder>
void Point14Codec::CodeReturnsXY(Coder& xy, Context& c, const Point14Fields& in, uint32_t changed) {
  Point14Fields& last = c.last;
  const uint32_t last_n = last.number_of_returns;
  const uint32_t last_r = last.return_number;
  const bool gps_change = (changed & kGpsTimeChanged) != 0;
  if (changed & kNumberOfReturnsChanged) last.number_of_returns = xy.Symbol(c.number_of_returns[last_n], in.number_of_returns);
  switch (changed & kReturnNumberMask) {
    case 1:
      last.return_number = (last_r + 1) % 16;
      break;
    case 2:
      last.return_number = (last_r + 15) % 16;
      break;
    case 3:
      if (gps_change) {
        last.return_number = xy.Symbol(c.return_number[last_r], in.return_number);
      } else {
        uint32_t step = 0;  // r = last_r + 2 + step (mod 16)
        if constexpr (Coder::kEncoding) step = (in.return_number + 16 - last_r) % 16 - 2;
        step = xy.Symbol(c.return_step_same_time, step);
        last.return_number = (last_r + step + 2) % 16;
      }
      break;
    default:
      break;
  }
  const uint32_t n = last.number_of_returns;
  const uint32_t r = last.return_number;
  const uint32_t slot = (ReturnContext4(n, r) << 1) | (gps_change ? 1 : 0);
  const uint32_t single = n == 1 ? 1 : 0;
  const int32_t dx = c.dx.Code(xy, c.median_x[slot].Get(), WrappingDiff(in.x, last.x), single);
  last.x = WrappingSum(last.x, dx);
  c.median_x[slot].Add(dx);
  const int32_t dy = c.dy.Code(xy, c.median_y[slot].Get(), WrappingDiff(in.y, last.y), single + LengthContext(c.dx.k(), 20));
  last.y = WrappingSum(last.y, dy);
  c.median_y[slot].Add(dy);
}

template <class Coder>
void Point14Codec::Code(Coder* coders, uint8_t* record) {
  constexpr bool kEnc = Coder::kEncoding;
  Point14Fields in;
  if constexpr (kEnc) in = Point14Fields::FromRecord(record);
  Context* c = contexts_[current_].get();
  const Point14Fields& prev = c->last;
  const uint32_t lpr = (prev.return_number == 1 ? 1u : 0u) + (prev.return_number >= prev.number_of_returns ? 2u : 0u) +
                       (prev.gps_time_changed ? 4u : 0u);
  uint32_t changed = 0;
  if constexpr (kEnc) {
    // Compared with the previous point of the point's own scanner channel (when that channel was seen before).
    const Context& own = in.scanner_channel != current_ && !contexts_[in.scanner_channel]->unused
                             ? *contexts_[in.scanner_channel]
                             : *c;
    const Point14Fields& cmp = own.last;
    changed = (in.scanner_channel != current_ ? kChannelChanged : 0) |
              (in.point_source != cmp.point_source ? kPointSourceChanged : 0) |
              (in.gps_time != cmp.gps_time ? kGpsTimeChanged : 0) |
              (in.scan_angle != cmp.scan_angle ? kScanAngleChanged : 0) |
              (in.number_of_returns != cmp.number_of_returns ? kNumberOfReturnsChanged : 0);
    if (in.return_number != cmp.return_number) {
      changed |= in.return_number == (cmp.return_number + 1) % 16    ? 1u
                 : in.return_number == (cmp.return_number + 15) % 16 ? 2u
                                                                      : 3u;
    }
  }
  Coder& xy = coders[kLayerReturnsXY];
  changed = xy.Symbol(c->changed_values[lpr], changed);
  item_context_ = 0;
  if (changed & kChannelChanged) {
    uint32_t step = 0;  // channel = current + 1 + step (mod 4)
    if constexpr (kEnc) step = (in.scanner_channel + 4 - current_) % 4 - 1;
    step = xy.Symbol(c->channel_step, step);
    const uint32_t channel = (current_ + step + 1) % 4;
    if (contexts_[channel]->unused) InitContext(channel, c->last);
    current_ = channel;
    item_context_ = channel;
    c = contexts_[channel].get();
    c->last.scanner_channel = channel;
  }
  Point14Fields& last = c->last;
  const bool gps_change = (changed & kGpsTimeChanged) != 0;
  const uint32_t time_bit = gps_change ? 1 : 0;
  CodeReturnsXY(xy, *c, in, changed);
  const uint32_t n = last.number_of_returns;
  const uint32_t r = last.return_number;
  const uint32_t cpr = (r == 1 ? 2u : 0u) + (r >= n ? 1u : 0u);  // first / last return
  const uint32_t single = n == 1 ? 1 : 0;

  if (kEnc || present_[kLayerZ]) {
    const uint32_t l = ReturnLevel(n, r);
    const uint32_t k_xy = (c->dx.k() + c->dy.k()) / 2;
    last.z = c->z.Code(coders[kLayerZ], c->last_z[l], in.z, single + LengthContext(k_xy, 18));
    c->last_z[l] = last.z;
  }
  if (kEnc || present_[kLayerClassification]) {
    const uint32_t slot = ((last.classification & 0x1F) << 1) + (cpr == 3 ? 1 : 0);
    const uint32_t v = coders[kLayerClassification].Symbol(c->classification[slot], in.classification);
    changed_[kLayerClassification] = changed_[kLayerClassification] || v != last.classification;
    last.classification = v;
  }
  if (kEnc || present_[kLayerFlags]) {
    const uint32_t last_flags = last.Flags();
    const uint32_t v = coders[kLayerFlags].Symbol(c->flags[last_flags], in.Flags());
    changed_[kLayerFlags] = changed_[kLayerFlags] || v != last_flags;
    last.edge = (v >> 5) & 1;
    last.scan_direction = (v >> 4) & 1;
    last.class_flags = v & 15;
  }
  if (kEnc || present_[kLayerIntensity]) {
    const uint32_t slot = (cpr << 1) | time_bit;
    const auto v = static_cast<uint16_t>(
        c->intensity.Code(coders[kLayerIntensity], c->last_intensity[slot], in.intensity, cpr));
    changed_[kLayerIntensity] = changed_[kLayerIntensity] || v != last.intensity;
    c->last_intensity[slot] = v;
    last.intensity = v;
  }
  if ((kEnc || present_[kLayerScanAngle]) && (changed & kScanAngleChanged)) {
    changed_[kLayerScanAngle] = true;
    last.scan_angle = static_cast<int16_t>(
        c->scan_angle.Code(coders[kLayerScanAngle], last.scan_angle, in.scan_angle, time_bit));
  }
  if (kEnc || present_[kLayerUserData]) {
    const uint32_t v = coders[kLayerUserData].Symbol(c->user_data[last.user_data / 4], in.user_data);
    changed_[kLayerUserData] = changed_[kLayerUserData] || v != last.user_data;
    last.user_data = v;
  }
  if ((kEnc || present_[kLayerPointSource]) && (changed & kPointSourceChanged)) {
    changed_[kLayerPointSource] = true;
    last.point_source =
        static_cast<uint16_t>(c->point_source.Code(coders[kLayerPointSource], last.point_source, in.point_source, 0));
  }
  if ((kEnc || present_[kLayerGpsTime]) && gps_change) {
    changed_[kLayerGpsTime] = true;
    last.gps_time = c->gps.Code(coders[kLayerGpsTime], in.gps_time);
  }
  last.gps_time_changed = gps_change;
  if constexpr (!kEnc) last.ToRecord(record);
}

template void Point14Codec::Code<Encoder>(Encoder*, uint8_t*);
template void Point14Codec::Code<Decoder>(Decoder*, uint8_t*);

}  // namespace sacfuse::laz
