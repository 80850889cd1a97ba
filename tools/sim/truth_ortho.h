#pragma once
// The reference orthophoto of a simulated block (`sacfuse simulate --truth-ortho-cell M`): the TRUE scene seen from
// straight above with the images' shading (Lambert, view-independent: tools/sim/surface.h Lighting), so it is what
// a perfect true orthophoto of the images shows. Cells of M metres on the global lattice of raster products
// (core/cell_window.h) over the simulated area, so it shares its cells with a run's DSM and ortho of that cell
// size; each cell the mean of 4 x 4 samples of albedo x shade (the normal from central differences of the height
// field over a quarter of a sample's spacing); an RGBA 8-bit Cloud Optimized GeoTIFF, alpha 0 where the surface is
// undefined.
#include <string>

#include "core/box2d.h"
#include "tools/sim/surface.h"

namespace sacfuse::sim {

// Writes the reference at `path`; `crs_wkt` as GDAL reads it ("" = none). Returns the cells written.
size_t WriteTruthOrtho(const Surface& surface, const Box2d& area, const Lighting& lighting, double cell_m,
                       const std::string& crs_wkt, const std::string& path);

}  // namespace sacfuse::sim
