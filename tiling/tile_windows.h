#pragma once
// Which part of a view's depth raster a tile needs: the 8 corners of the tile's halo box at the block's height
// range are projected into the view; their bounding rectangle, padded by a margin and clipped to the raster, is
// the window. For a pinhole camera the projection of the box lies inside the hull of its corners' projections,
// so the window holds every pixel that can see the box.
#include <optional>

#include "core/camera.h"
#include "core/view.h"
#include "tiling/footprint.h"

namespace sacfuse {

// Half-open pixel rectangle of a raster: rows [row_begin, row_end), cols [col_begin, col_end).
struct PixelWindow {
  int row_begin = 0, row_end = 0;
  int col_begin = 0, col_end = 0;
  int width() const { return col_end - col_begin; }
  int height() const { return row_end - row_begin; }
  size_t num_pixels() const { return static_cast<size_t>(width()) * height(); }
  bool operator==(const PixelWindow& o) const {
    return row_begin == o.row_begin && row_end == o.row_end && col_begin == o.col_begin && col_end == o.col_end;
  }
};

// The window of `view`'s raster of raster_width x raster_height (e.g. its depth map; intrinsics are scaled from
// the image size) that covers the box `xy` x [z_min_m, z_max_m], padded by margin_px and clipped; nullopt when
// the view does not see the box (every corner behind the camera, or the projection misses the raster). When
// some corners are behind the camera and some in front, the whole raster is returned (conservative).
std::optional<PixelWindow> ViewWindowForBox(const View& view, int raster_width, int raster_height,
                                            const Bounds2d& xy, double z_min_m, double z_max_m, int margin_px);

// The camera of a window: `camera_at_raster` (intrinsics at the full raster's resolution) with the principal
// point shifted by the window origin and the window's size, so pixel (r, c) of the window is pixel
// (r + row_begin, c + col_begin) of the raster.
PinholeCamera WindowCamera(const PinholeCamera& camera_at_raster, const PixelWindow& window);

}  // namespace sacfuse
