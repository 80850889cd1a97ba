#pragma once
// Which part of a view's depth raster a tile needs: the 8 corners of the tile's halo box at the block's height
// range are projected into the view; their bounding rectangle, padded by a margin and clipped to the raster, is
// the window. For a pinhole camera the projection of the box lies inside the hull of its corners' projections,
// so the window holds every pixel that can see the box.
#include <optional>

#include "core/camera.h"
#include "core/pixel_window.h"
#include "core/view.h"
#include "tiling/footprint.h"

namespace sacfuse {


// The window of `view`'s raster of raster_width x raster_height (e.g. its depth map; intrinsics are scaled from
// the image size) that covers the box `xy` x [z_min_m, z_max_m], padded by margin_px and clipped; nullopt when
// the view does not see the box (every corner behind the camera, or the projection misses the raster). When
// some corners are behind the camera and some in front, the whole raster is returned (conservative).
std::optional<PixelWindow> ViewWindowForBox(const View& view, int raster_width, int raster_height,
                                            const Box2d& xy, double z_min_m, double z_max_m, int margin_px);

// The camera of a window: `camera_at_raster` (intrinsics at the full raster's resolution) with the principal
// point shifted by the window origin and the window's size, so pixel (r, c) of the window is pixel
// (r + row_begin, c + col_begin) of the raster.
PinholeCamera WindowCamera(const PinholeCamera& camera_at_raster, const PixelWindow& window);

}  // namespace sacfuse
