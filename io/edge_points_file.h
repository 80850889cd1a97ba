#pragma once
// The points a tile fused outside its own cells (jobs/dsm_product.h): SAC keeps a pixel in the tile whose core
// holds the pixel's own point, but the fused point (a combination of several views' points) may land a little
// beyond that core, in a neighbouring tile's cells (up to ~0.8 m on the tiny simulated block). A raster product
// built per tile records those points here, DIR/tiles/<id>.dsm_edge.bin, so the assembly can give each cell all
// of its points whichever tile fused them.
// Format (little-endian): the 16-byte magic "sacfuse-edge-v1\n", uint64 count, then count records of three
// float64 (x, y, z in metres, exactly the coordinates read from the tile's LAS file). Written atomically.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

void WriteEdgePointsFile(const std::string& path, const std::vector<Eigen::Vector3d>& points);
// Throws InputError naming the file when it is missing, truncated or not such a file.
std::vector<Eigen::Vector3d> ReadEdgePointsFile(const std::string& path);

}  // namespace sacfuse
