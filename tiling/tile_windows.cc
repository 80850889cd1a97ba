#include "tiling/tile_windows.h"

#include <algorithm>
#include <cmath>

namespace sacfuse {

std::optional<PixelWindow> ViewWindowForBox(const View& view, int raster_width, int raster_height,
                                            const Box2d& xy, double z_min_m, double z_max_m, int margin_px) {
  if (xy.IsEmpty() || raster_width <= 0 || raster_height <= 0) return std::nullopt;
  const PinholeCamera camera = view.camera.Scaled(raster_width, raster_height);
  double u_min = 1e300, u_max = -1e300, v_min = 1e300, v_max = -1e300;
  int in_front = 0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner((i & 1) ? xy.max.x() : xy.min.x(), (i & 2) ? xy.max.y() : xy.min.y(),
                                 (i & 4) ? z_max_m : z_min_m);
    const Eigen::Vector3d p = view.cam_from_world * corner;
    if (p.z() <= 1e-9) continue;
    ++in_front;
    const Eigen::Vector2d uv = camera.Project(p);
    u_min = std::min(u_min, uv.x());
    u_max = std::max(u_max, uv.x());
    v_min = std::min(v_min, uv.y());
    v_max = std::max(v_max, uv.y());
  }
  if (in_front == 0) return std::nullopt;
  if (in_front < 8) return PixelWindow{0, raster_height, 0, raster_width};
  // Does the projected rectangle touch the raster [0, W) x [0, H) at all?
  if (u_max < 0 || v_max < 0 || u_min >= raster_width || v_min >= raster_height) return std::nullopt;
  const auto clamp = [](double v, int hi) { return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(hi))); };
  PixelWindow w;
  w.col_begin = clamp(std::floor(u_min) - margin_px, raster_width);
  w.col_end = clamp(std::ceil(u_max) + margin_px, raster_width);
  w.row_begin = clamp(std::floor(v_min) - margin_px, raster_height);
  w.row_end = clamp(std::ceil(v_max) + margin_px, raster_height);
  if (w.width() <= 0 || w.height() <= 0) return std::nullopt;
  return w;
}

PinholeCamera WindowCamera(const PinholeCamera& camera_at_raster, const PixelWindow& window) {
  PinholeCamera c = camera_at_raster;
  c.width = window.width();
  c.height = window.height();
  c.cx -= window.col_begin;
  c.cy -= window.row_begin;
  return c;
}

}  // namespace sacfuse
