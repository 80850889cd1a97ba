#include "report/report_profile_sources.h"

#include <algorithm>

#include "core/backproject.h"
#include "io/las_reader.h"
#include "tiling/tile_windows.h"

namespace sacfuse {
namespace {
constexpr size_t kLasChunk = 1 << 16;
}  // namespace

void SampleLasInStrip(const std::vector<std::string>& las_paths, const ProfileStrip& strip, ProfileSample* sample,
                      bool keep_source_id) {
  const Box2d box = strip.Box();
  std::vector<LasPoint> chunk;
  for (const std::string& path : las_paths) {
    LasReader reader(path);
    const LasHeader& h = reader.header();
    Box2d file_box;
    file_box.Extend(Eigen::Vector2d(h.min.x(), h.min.y()));
    file_box.Extend(Eigen::Vector2d(h.max.x(), h.max.y()));
    if (h.point_count == 0 || !file_box.Intersects(box)) continue;
    while (reader.Read(&chunk, kLasChunk) > 0) {
      for (const LasPoint& p : chunk) {
        if (p.xyz.x() < box.min.x() || p.xyz.x() > box.max.x() || p.xyz.y() < box.min.y() ||
            p.xyz.y() > box.max.y()) {
          continue;
        }
        if (const auto s = strip.Along(p.xyz.x(), p.xyz.y())) {
          sample->Add({static_cast<float>(*s), static_cast<float>(p.xyz.z()),
                       keep_source_id ? p.point_source_id : uint16_t{0}});
        }
      }
    }
  }
}

DepthStripStats SampleDepthInStrip(const DepthBlock& input, const ProfileStrip& strip, ProfileSample* sample) {
  DepthStripStats stats;
  const Box2d box = strip.Box();
  for (const View& view : input.views()) {
    const DepthRasterSize size = input.DepthSize(view);
    const std::optional<PixelWindow> window =
        ViewWindowForBox(view, size.width, size.height, box, strip.z_min_m, strip.z_max_m, /*margin_px=*/1);
    if (!window) continue;
    ++stats.views_read;
    const PinholeCamera camera = view.camera.Scaled(size.width, size.height);
    const Rigid3d world_from_cam = view.cam_from_world.Inverse();
    const auto source_id = static_cast<uint16_t>(std::min<uint32_t>(view.index + 1, 65535));
    for (int row0 = window->row_begin; row0 < window->row_end; row0 += kProfileDepthBandRows) {
      const PixelWindow band{row0, std::min(window->row_end, row0 + kProfileDepthBandRows), window->col_begin,
                             window->col_end};
      const DepthMap depth = input.ReadDepthWindow(view, band);
      stats.window_pixels += band.num_pixels();
      for (int r = 0; r < depth.height; ++r) {
        for (int c = 0; c < depth.width; ++c) {
          const float d = depth.at(r, c);
          if (!IsValidDepth(d)) continue;
          const Eigen::Vector3d p =
              DepthPixelToWorld(camera, world_from_cam, band.col_begin + c, band.row_begin + r, d);
          if (const auto s = strip.Along(p.x(), p.y())) {
            sample->Add({static_cast<float>(*s), static_cast<float>(p.z()), source_id});
          }
        }
      }
    }
  }
  return stats;
}

}  // namespace sacfuse
