#include "report/report_profile_sources.h"

#include <algorithm>
#include <exception>

#include <tbb/parallel_for.h>

#include "core/backproject.h"
#include "io/las_reader.h"
#include "tiling/tile_windows.h"

namespace sacfuse {
namespace {
constexpr size_t kLasChunk = 1 << 16;
constexpr size_t kFilterBlock = 4096;  // points of a chunk tested per task
}  // namespace

void SampleLasInStrip(const std::vector<std::string>& las_paths, const ProfileStrip& strip, ProfileSample* sample,
                      bool keep_source_id) {
  const Box2d box = strip.Box();
  std::vector<LasPoint> chunk;
  std::vector<std::vector<ProfilePoint>> found;  // per block of a chunk, in order
  for (const std::string& path : las_paths) {
    LasReader reader(path);
    const LasHeader& h = reader.header();
    Box2d file_box;
    file_box.Extend(Eigen::Vector2d(h.min.x(), h.min.y()));
    file_box.Extend(Eigen::Vector2d(h.max.x(), h.max.y()));
    if (h.point_count == 0 || !file_box.Intersects(box)) continue;
    while (reader.Read(&chunk, kLasChunk) > 0) {
      // The strip's points of each block found in parallel, then added in the file's order (the sample's random
      // choice depends on it).
      found.resize((chunk.size() + kFilterBlock - 1) / kFilterBlock);
      tbb::parallel_for(size_t{0}, found.size(), [&](size_t b) {
        found[b].clear();
        for (size_t i = b * kFilterBlock; i < std::min(chunk.size(), (b + 1) * kFilterBlock); ++i) {
          const LasPoint& p = chunk[i];
          if (p.xyz.x() < box.min.x() || p.xyz.x() > box.max.x() || p.xyz.y() < box.min.y() ||
              p.xyz.y() > box.max.y()) {
            continue;
          }
          if (const auto s = strip.Along(p.xyz.x(), p.xyz.y())) {
            found[b].push_back({static_cast<float>(*s), static_cast<float>(p.xyz.z()),
                                keep_source_id ? p.point_source_id : uint16_t{0}});
          }
        }
      });
      for (const std::vector<ProfilePoint>& points : found) {
        for (const ProfilePoint& p : points) sample->Add(p);
      }
    }
  }
}

DepthStripStats SampleDepthInStrip(const DepthBlock& input, const ProfileStrip& strip, ProfileSample* sample) {
  const Box2d box = strip.Box();
  const std::vector<View>& views = input.views();
  // Each view's points in the strip gathered in parallel (a view's are few: the strip is 2 GSD wide), then added
  // in view order (the sample's random choice depends on it); the first unreadable view in that order throws.
  struct ViewStrip {
    bool read = false;
    uint64_t window_pixels = 0;
    std::vector<ProfilePoint> points;
    std::exception_ptr error;
  };
  std::vector<ViewStrip> per_view(views.size());
  const auto gather = [&](const View& view, ViewStrip& out) {
    const DepthRasterSize size = input.DepthSize(view);
    const std::optional<PixelWindow> window =
        ViewWindowForBox(view, size.width, size.height, box, strip.z_min_m, strip.z_max_m, /*margin_px=*/1);
    if (!window) return;
    out.read = true;
    const PinholeCamera camera = view.camera.Scaled(size.width, size.height);
    const Rigid3d world_from_cam = view.cam_from_world.Inverse();
    const auto source_id = static_cast<uint16_t>(std::min<uint32_t>(view.index + 1, 65535));
    for (int row0 = window->row_begin; row0 < window->row_end; row0 += kProfileDepthBandRows) {
      const PixelWindow band{row0, std::min(window->row_end, row0 + kProfileDepthBandRows), window->col_begin,
                             window->col_end};
      const DepthMap depth = input.ReadDepthWindow(view, band);
      out.window_pixels += band.num_pixels();
      for (int r = 0; r < depth.height; ++r) {
        for (int c = 0; c < depth.width; ++c) {
          const float d = depth.at(r, c);
          if (!IsValidDepth(d)) continue;
          const Eigen::Vector3d p =
              DepthPixelToWorld(camera, world_from_cam, band.col_begin + c, band.row_begin + r, d);
          if (const auto s = strip.Along(p.x(), p.y())) {
            out.points.push_back({static_cast<float>(*s), static_cast<float>(p.z()), source_id});
          }
        }
      }
    }
  };
  tbb::parallel_for(size_t{0}, views.size(), size_t{1}, [&](size_t v) {
    try {
      gather(views[v], per_view[v]);
    } catch (...) {
      per_view[v].error = std::current_exception();
    }
  });
  DepthStripStats stats;
  for (const ViewStrip& v : per_view) {
    if (v.error) std::rethrow_exception(v.error);
    stats.views_read += v.read ? 1 : 0;
    stats.window_pixels += v.window_pixels;
    for (const ProfilePoint& p : v.points) sample->Add(p);
  }
  return stats;
}

}  // namespace sacfuse
