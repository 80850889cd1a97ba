#include "io/laz_layered_items.h"

#include <cstring>

#include "io/las_format.h"
#include "io/laz_common.h"

namespace sacfuse::laz {
namespace lf = las_format;

namespace {

template <class Coder>
uint8_t CodeByteDiff(Coder& coder, SymbolModel& model, uint8_t last, uint8_t value) {
  return ByteSum(coder.Symbol(model, ByteDiff(value, last)), last);
}

}  // namespace

// ------------------------------------------------------------------------------------------- RGB14 / RGBNIR14

void Rgb14Codec::Init(uint32_t context, const std::array<uint16_t, 3>& rgb, uint16_t nir) {
  Context& c = contexts_[context];
  c.rgb_models.Reset();
  c.nir_models.Reset();
  c.rgb = rgb;
  c.nir = nir;
  c.unused = false;
}

void Rgb14Codec::Reset(const uint8_t* first, uint32_t context, const bool* present) {
  for (Context& c : contexts_) c.unused = true;
  current_ = context;
  Init(context, {lf::GetU16(first), lf::GetU16(first + 2), lf::GetU16(first + 4)},
       with_nir_ ? lf::GetU16(first + 6) : uint16_t{0});
  for (size_t i = 0; i < layers(); ++i) present_[i] = present[i];
  changed_ = {false, false};
}

template <class Coder>
void Rgb14Codec::Code(Coder* coders, uint8_t* item, uint32_t context) {
  constexpr bool kEnc = Coder::kEncoding;
  Context* values = &contexts_[current_];  // whose previous values predict
  if (context != current_) {
    current_ = context;
    if (contexts_[current_].unused) {
      const std::array<uint16_t, 3> rgb = values->rgb;
      Init(current_, rgb, values->nir);
      values = &contexts_[current_];
    }
  }
  Context& models = contexts_[current_];
  std::array<uint16_t, 3> rgb = values->rgb;
  uint16_t nir = values->nir;
  if constexpr (kEnc) {
    rgb = {lf::GetU16(item), lf::GetU16(item + 2), lf::GetU16(item + 4)};
    if (with_nir_) nir = lf::GetU16(item + 6);
  }
  if (kEnc || present_[0]) {
    if (CodeRgb(coders[0], models.rgb_models, values->rgb, rgb) != 0) changed_[0] = true;
  }
  if (with_nir_ && (kEnc || present_[1])) {
    if (CodeNir(coders[1], models.nir_models, values->nir, nir) != 0) changed_[1] = true;
  }
  if constexpr (!kEnc) {
    for (int c = 0; c < 3; ++c) lf::PutU16(item + 2 * c, rgb[c]);
    if (with_nir_) lf::PutU16(item + 6, nir);
  }
}

template void Rgb14Codec::Code<Encoder>(Encoder*, uint8_t*, uint32_t);
template void Rgb14Codec::Code<Decoder>(Decoder*, uint8_t*, uint32_t);

// ------------------------------------------------------------------------------------------------------ BYTE14

Byte14Codec::Byte14Codec(size_t count) : count_(count), present_(count), changed_(count) {
  for (Context& c : contexts_) {
    c.last.resize(count);
    c.models.assign(count, SymbolModel(256));
  }
}

void Byte14Codec::Init(uint32_t context, const std::vector<uint8_t>& from) {
  Context& c = contexts_[context];
  for (SymbolModel& m : c.models) m.Reset();
  c.last = from;
  c.unused = false;
}

void Byte14Codec::Reset(const uint8_t* first, uint32_t context, const bool* present) {
  for (Context& c : contexts_) c.unused = true;
  current_ = context;
  Init(context, std::vector<uint8_t>(first, first + count_));
  for (size_t i = 0; i < count_; ++i) {
    present_[i] = present[i];
    changed_[i] = false;
  }
}

template <class Coder>
void Byte14Codec::Code(Coder* coders, uint8_t* item, uint32_t context) {
  constexpr bool kEnc = Coder::kEncoding;
  Context* values = &contexts_[current_];
  if (context != current_) {
    current_ = context;
    if (contexts_[current_].unused) {
      const std::vector<uint8_t> from = values->last;
      Init(current_, from);
      values = &contexts_[current_];
    }
  }
  Context& models = contexts_[current_];
  for (size_t i = 0; i < count_; ++i) {
    uint8_t v = values->last[i];
    if (kEnc || present_[i]) {
      v = CodeByteDiff(coders[i], models.models[i], values->last[i], item[i]);
      if (v != values->last[i]) changed_[i] = true;
      values->last[i] = v;
    }
    if constexpr (!kEnc) item[i] = v;
  }
}

template void Byte14Codec::Code<Encoder>(Encoder*, uint8_t*, uint32_t);
template void Byte14Codec::Code<Decoder>(Decoder*, uint8_t*, uint32_t);

// -------------------------------------------------------------------------------------------------- BYTE v2

void BytesCodec::Reset(const uint8_t* first) {
  for (SymbolModel& m : models_) m.Reset();
  std::memcpy(last_.data(), first, last_.size());
}

template <class Coder>
void BytesCodec::Code(Coder& coder, uint8_t* item) {
  for (size_t i = 0; i < last_.size(); ++i) {
    last_[i] = CodeByteDiff(coder, models_[i], last_[i], item[i]);
    if constexpr (!Coder::kEncoding) item[i] = last_[i];
  }
}

template void BytesCodec::Code<Encoder>(Encoder&, uint8_t*);
template void BytesCodec::Code<Decoder>(Decoder&, uint8_t*);

}  // namespace sacfuse::laz
