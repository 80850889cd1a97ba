#pragma once
// The items that follow Point14 in layered (version 3) chunks: RGB14 (one layer), RGBNIR14 (an RGB and a NIR
// layer) and BYTE14 extra bytes (one layer per byte). Like Point14 they keep one context per scanner channel and
// switch with the channel Point14 reports. Quirk of version 3 kept for compatibility: when the channel switches
// to a context already seen in the chunk, prediction still uses the values of the context left. Private to
// io/laz_*.
#include <array>
#include <cstdint>
#include <vector>

#include "io/laz_arithmetic.h"
#include "io/laz_rgb.h"

namespace sacfuse::laz {

class Rgb14Codec {
 public:
  explicit Rgb14Codec(bool with_nir) : with_nir_(with_nir) {}
  size_t size() const { return with_nir_ ? 8 : 6; }
  size_t layers() const { return with_nir_ ? 2 : 1; }
  // Start of a chunk; present[i] for i < layers() (decoding; the encoder passes all true).
  void Reset(const uint8_t* first, uint32_t context, const bool* present);
  // Encoder: compresses *item; decoder: writes the next item. coders[i] is the coder of layer i.
  template <class Coder>
  void Code(Coder* coders, uint8_t* item, uint32_t context);
  bool changed(size_t layer) const { return changed_[layer]; }

 private:
  struct Context {
    bool unused = true;
    std::array<uint16_t, 3> rgb{};
    uint16_t nir = 0;
    RgbModels rgb_models;
    NirModels nir_models;
  };
  void Init(uint32_t context, const std::array<uint16_t, 3>& rgb, uint16_t nir);

  bool with_nir_;
  std::array<Context, 4> contexts_;
  uint32_t current_ = 0;
  std::array<bool, 2> present_{};
  std::array<bool, 2> changed_{};
};

class Byte14Codec {
 public:
  explicit Byte14Codec(size_t count);
  size_t size() const { return count_; }
  size_t layers() const { return count_; }
  void Reset(const uint8_t* first, uint32_t context, const bool* present);
  template <class Coder>
  void Code(Coder* coders, uint8_t* item, uint32_t context);
  bool changed(size_t layer) const { return changed_[layer]; }

 private:
  struct Context {
    bool unused = true;
    std::vector<uint8_t> last;
    std::vector<SymbolModel> models;
  };
  void Init(uint32_t context, const std::vector<uint8_t>& from);

  size_t count_;
  std::array<Context, 4> contexts_;
  uint32_t current_ = 0;
  std::vector<bool> present_;
  std::vector<bool> changed_;
};

// BYTE item version 2 (point-wise extra bytes): each byte coded as its difference to the previous point's.
class BytesCodec {
 public:
  explicit BytesCodec(size_t count) : last_(count), models_(count, SymbolModel(256)) {}
  size_t size() const { return last_.size(); }
  void Reset(const uint8_t* first);
  template <class Coder>
  void Code(Coder& coder, uint8_t* item);

 private:
  std::vector<uint8_t> last_;
  std::vector<SymbolModel> models_;
};

}  // namespace sacfuse::laz
