#pragma once
// COLMAP's fused.ply (local float32 coordinates) -> a LAS file in the block's CRS, streaming in chunks.
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "io/las_writer.h"

namespace sacfuse {

// Every vertex becomes one LAS point at xyz + offset (the addition done in double), RGB from the PLY's 8-bit
// colour x 256 (as sacfuse's own output), return 1 of 1, point source ID 0 (a fused point comes from several
// views; the spec's value for "no single source"). When options.offset is unset it is set to `offset` snapped
// down to 1000 m. Returns the number of points written. Throws InputError for a bad PLY and Error from the writer.
uint64_t ConvertPlyToLas(const std::string& ply_path, const std::string& las_path, const Eigen::Vector3d& offset,
                         LasWriterOptions options);

}  // namespace sacfuse
