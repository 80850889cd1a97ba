#pragma once
// Colour coding of the LASzip format: RGB12 item version 2 and the RGB / NIR layers of RGB14 and RGBNIR14
// version 3 use the same per-point scheme. A mask says which bytes of R, G, B changed (and whether the channels
// differ at all); red is coded as a byte difference, green and blue as corrections to red's change.
// Private to io/laz_*.
#include <array>
#include <cstdint>

#include "io/laz_models.h"

namespace sacfuse::laz {

struct RgbModels {
  SymbolModel used{128};  // which bytes changed (bits 0-5) and "channels differ" (bit 6)
  std::array<SymbolModel, 6> diff{SymbolModel(256), SymbolModel(256), SymbolModel(256),
                                  SymbolModel(256), SymbolModel(256), SymbolModel(256)};
  void Reset() {
    used.Reset();
    for (SymbolModel& m : diff) m.Reset();
  }
};

struct NirModels {
  SymbolModel used{4};  // which of the two bytes changed
  std::array<SymbolModel, 2> diff{SymbolModel(256), SymbolModel(256)};
  void Reset() {
    used.Reset();
    for (SymbolModel& m : diff) m.Reset();
  }
};

// Encoder: codes rgb (predicted from last) and returns the change mask; decoder: decodes into rgb. Either way
// `last` becomes rgb.
template <class Coder>
uint32_t CodeRgb(Coder& coder, RgbModels& models, std::array<uint16_t, 3>& last, std::array<uint16_t, 3>& rgb);
template <class Coder>
uint32_t CodeNir(Coder& coder, NirModels& models, uint16_t& last, uint16_t& nir);

}  // namespace sacfuse::laz
