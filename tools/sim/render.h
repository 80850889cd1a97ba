#pragma once
// Rendering one view of a Surface: z-buffer rasterisation of the height field's triangles into a depth raster,
// then per pixel back-projection of the depth to the 3D point, albedo and Lambert shading -> RGB image.
//
// The height field is sampled on world-aligned grids whose spacing is a power of two close to `sampling` times
// the local GSD (range / focal), chosen per 2D tile of the view's footprint, so obliques get coarser samples far
// away. Grids of neighbouring tiles overlap by one sample (no cracks). Triangles spanning a height jump form the
// (near-)vertical walls that obliques see. Depth is interpolated perspective-correctly (1/z linear in the image),
// so a planar facet is rendered exactly. Tiles are rasterised in parallel (OpenMP) into an atomic z-buffer that
// packs (depth bits, facet normal), so the result does not depend on thread scheduling.
#include <cstddef>

#include "core/camera.h"
#include "core/raster.h"
#include "core/rigid3.h"
#include "tools/sim/surface.h"

namespace sacfuse::sim {

struct RenderRequest {
  const Surface* surface = nullptr;
  PinholeCamera camera;            // image resolution
  Rigid3d cam_from_world;          // the TRUE pose
  int depth_width = 0;             // depth raster size (0 = the image size)
  int depth_height = 0;
  Lighting lighting;
  bool render_image = true;        // false: depth only
  double sampling = 0.5;           // sample spacing / local GSD (before rounding to a power of two)
};

struct RenderedView {
  RgbImage image;        // camera.width x camera.height (empty when !render_image)
  DepthMap depth;        // depth_width x depth_height, z-depth in metres, 0 where nothing was hit
  size_t tiles = 0;      // footprint tiles rasterised
  size_t triangles = 0;  // triangles rasterised
};

RenderedView RenderView(const RenderRequest& request);

// Power of two nearest (in log scale) to x > 0, e.g. 0.05 -> 0.0625.
double NearestPowerOfTwo(double x);

}  // namespace sacfuse::sim
