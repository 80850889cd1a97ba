#pragma once
// View-independent albedo of the procedural city, with real edges that superpixels can follow: per-building roof
// colours with tile rows or solar panels, façades with a window grid by storey and position along the wall,
// asphalt with lane markings and zebra crossings, paved sidewalks, multi-octave noise on grass and canopies.
// All coordinates are city-frame metres (see city_layout.h); albedo is RGB in [0, 1].
#include <cstdint>

#include <Eigen/Core>

#include "tools/sim/city_layout.h"

namespace sacfuse::sim {

// Roof at building-local (a, b) (see Building::ToLocal).
Eigen::Vector3f RoofAlbedo(const Building& b, double a, double bb, uint64_t seed);
// Façade at `along` metres from the wall's start and `h` metres above the building's base.
Eigen::Vector3f FacadeAlbedo(const Building& b, double along, double h, uint64_t seed);
Eigen::Vector3f TreeAlbedo(const Tree& t, double u, double v, uint64_t seed);
// Roads, sidewalks, parks, courtyards and parking lots.
Eigen::Vector3f GroundAlbedo(const CityLayout& layout, double u, double v, uint64_t seed);

}  // namespace sacfuse::sim
