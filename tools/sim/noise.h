#pragma once
// Smooth seeded 2D noise for procedural textures and terrain: value noise on a unit lattice (quintic
// interpolation) and its multi-octave sum. Values are in [-1, 1]; callers pass LOCAL coordinates (metres from
// the scene origin), never raw UTM values, to keep precision.
#include <cstdint>

namespace sacfuse::sim {

// Value noise with lattice spacing 1; continuous, C2 between cells.
double ValueNoise(uint64_t seed, double x, double y);

// Fractal sum of `octaves` ValueNoise layers: wavelength `wavelength` for the first, halved per octave, amplitude
// multiplied by `gain` per octave; normalised to [-1, 1].
double Fbm(uint64_t seed, double x, double y, double wavelength, int octaves, double gain = 0.5);

// Uniform [0, 1) hash of an integer lattice cell (e.g. one paving slab, one window).
double CellHash(uint64_t seed, int64_t i, int64_t j);

}  // namespace sacfuse::sim
