#pragma once
// Normal maps as an MVS tool would write them, from the FINAL (noisy) depth: per valid pixel a least-squares
// plane through the back-projected 3x3 neighbourhood (neighbours within max(0.3 m, 4 pixel footprints) of the
// centre's depth, so planes do not straddle depth edges), oriented toward the camera (edge-on planes tilted
// to face it by >= ~3 degrees). Camera frame, unit length,
// 0 where the depth is invalid; a pixel without enough neighbours gets the reversed viewing ray.
#include "core/camera.h"
#include "core/raster.h"

namespace sacfuse::sim {

NormalMap NormalsFromDepth(const DepthMap& depth, const PinholeCamera& depth_camera);

}  // namespace sacfuse::sim
