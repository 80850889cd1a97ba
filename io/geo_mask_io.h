#pragma once
// GeoMask on disk: an 8-bit PNG (255 = inside, 0 = outside; row 0 = north) plus a JSON sidecar
// "<png path without extension>.json" holding {origin_x, origin_y, cell_size_m, width, height, crs}.
#include <string>

#include "core/geo_mask.h"

namespace sacfuse {

void WriteGeoMask(const std::string& png_path, const GeoMask& mask, const std::string& crs = "");
GeoMask ReadGeoMask(const std::string& png_path);

}  // namespace sacfuse
