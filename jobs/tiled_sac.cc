#include "jobs/tiled_sac.h"

#include <algorithm>
#include <filesystem>
#include <vector>


#include "core/error.h"
#include "io/colmap_array.h"
#include "io/superpixel_io.h"
#include "jobs/superpixel_cache.h"

namespace sacfuse {
namespace {

// Computes and caches a view's superpixels unless a matching cache file exists (then nothing is read).
bool EnsureSuperpixels(const ColmapWorkspace& workspace, const View& view, const DepthRasterSize& size,
                       const SuperpixelOptions& options, const std::string& cache_dir) {
  if (SuperpixelCacheIsCurrent(cache_dir, view.name, size.width, size.height, options)) return false;
  const DepthMap depth = workspace.ReadDepthMap(view);
  const RgbImage image = workspace.ReadImage(view);
  bool computed = false;
  LoadOrComputeSuperpixels(cache_dir, view.name, image, depth, options, &computed);
  return computed;
}

// Columns [col_begin, col_end) of a raster holding whole rows.
template <typename T>
Raster<T> CropColumns(const Raster<T>& rows, int col_begin, int col_end) {
  Raster<T> out(col_end - col_begin, rows.height, rows.channels);
  const size_t row_values = static_cast<size_t>(out.width) * rows.channels;
  for (int r = 0; r < rows.height; ++r) {
    const T* src = rows.data.data() + (static_cast<size_t>(r) * rows.width + col_begin) * rows.channels;
    std::copy(src, src + row_values, out.data.data() + static_cast<size_t>(r) * row_values);
  }
  return out;
}

// The rasters of one view inside one tile, owned here; SacView points into them.
struct WindowRasters {
  DepthMap depth;
  SuperpixelMap superpixels;
  RgbImage image;  // at depth-window resolution
};

WindowRasters LoadWindow(const ColmapWorkspace& workspace, const View& view, const DepthRasterSize& size,
                         const PixelWindow& w, const std::string& cache_dir) {
  WindowRasters out;
  out.depth = CropColumns(ReadColmapArrayRows(workspace.DepthMapPath(view), w.row_begin, w.row_end), w.col_begin,
                          w.col_end);
  const SuperpixelMap rows = ReadSuperpixelRows(SuperpixelCachePath(cache_dir, view.name), w.row_begin, w.row_end);
  if (rows.width != size.width) {
    throw InputError(SuperpixelCachePath(cache_dir, view.name), "superpixel raster is not the depth map's size");
  }
  out.superpixels.width = w.width();
  out.superpixels.height = w.height();
  out.superpixels.labels.resize(w.num_pixels());
  for (int r = 0; r < w.height(); ++r) {
    std::copy_n(rows.labels.begin() + static_cast<size_t>(r) * rows.width + w.col_begin, w.width(),
                out.superpixels.labels.begin() + static_cast<size_t>(r) * w.width());
  }
  out.superpixels.clusters = rows.clusters;  // same indices; centroids into window coordinates
  for (SuperpixelCluster& c : out.superpixels.clusters) {
    c.centroid_col -= static_cast<float>(w.col_begin);
    c.centroid_row -= static_cast<float>(w.row_begin);
  }
  // Colour at depth resolution, sampled exactly as core's untiled colour lookup samples the full image.
  const RgbImage full = workspace.ReadImage(view);
  if (!full.empty()) {
    out.image = RgbImage(w.width(), w.height(), full.channels);
    for (int r = 0; r < w.height(); ++r) {
      const int ir = std::min(full.height - 1, static_cast<int>((r + w.row_begin + 0.5) * full.height / size.height));
      for (int c = 0; c < w.width(); ++c) {
        const int ic = std::min(full.width - 1, static_cast<int>((c + w.col_begin + 0.5) * full.width / size.width));
        for (int ch = 0; ch < full.channels; ++ch) out.image.at(r, c, ch) = full.at(ir, ic, ch);
      }
    }
  }
  return out;
}

// Forwards the points of one tile's core; the rest belong to neighbouring tiles.
class CoreFilterSink : public PointSink {
 public:
  CoreFilterSink(const TileGrid& grid, const TileIndex& tile, PointSink& next)
      : grid_(grid), tile_(tile), next_(next) {}
  void Write(const FusedPoint* points, size_t count) override {
    kept_.clear();
    for (size_t i = 0; i < count; ++i) {
      const Eigen::Vector3d& p = points[i].point_in_world;
      if (grid_.TileOf(p.x(), p.y()) == tile_) kept_.push_back(points[i]);
    }
    outside_ += count - kept_.size();
    inside_ += kept_.size();
    if (!kept_.empty()) next_.Write(kept_.data(), kept_.size());
  }
  uint64_t inside() const { return inside_; }
  uint64_t outside() const { return outside_; }

 private:
  const TileGrid& grid_;
  TileIndex tile_;
  PointSink& next_;
  std::vector<FusedPoint> kept_;
  uint64_t inside_ = 0, outside_ = 0;
};

}  // namespace

void AddSacStats(const SacStats& s, SacStats* total) {
  total->nodes += s.nodes;
  total->valid_nodes += s.valid_nodes;
  total->mean_correspondences += s.mean_correspondences * s.valid_nodes;  // normalised at the end
  total->labeling.netlets += s.labeling.netlets;
  total->labeling.proven_optimal += s.labeling.proven_optimal;
  if (total->labeling.size_histogram.size() < s.labeling.size_histogram.size()) {
    total->labeling.size_histogram.resize(s.labeling.size_histogram.size(), 0);
  }
  for (size_t i = 0; i < s.labeling.size_histogram.size(); ++i) {
    total->labeling.size_histogram[i] += s.labeling.size_histogram[i];
  }
  total->labeling.nodes_keeping_own_view += s.labeling.nodes_keeping_own_view;
  total->labeling.nodes_relabelled += s.labeling.nodes_relabelled;
  total->collapse += s.collapse;
  for (const auto& [stage, secs] : s.stage_seconds) {
    auto it = std::find_if(total->stage_seconds.begin(), total->stage_seconds.end(),
                           [&](const auto& e) { return e.first == stage; });
    if (it == total->stage_seconds.end()) {
      total->stage_seconds.emplace_back(stage, secs);
    } else {
      it->second += secs;
    }
  }
}

size_t EnsureTiledSuperpixels(const ColmapWorkspace& workspace, const TilePlan& plan, const SacOptions& options,
                              const std::string& superpixel_cache_dir, const SacProgress& progress,
                              const PlannedTile* only_tile) {
  const auto& views = workspace.views();
  std::vector<size_t> todo;
  if (only_tile == nullptr) {
    for (size_t v = 0; v < views.size(); ++v) todo.push_back(v);
  } else {
    for (const TileViewWindow& tw : only_tile->views) todo.push_back(tw.view);
  }
  size_t computed = 0;
  for (size_t i = 0; i < todo.size(); ++i) {
    const size_t v = todo[i];
    computed += EnsureSuperpixels(workspace, views[v], plan.depth_sizes[v], options.superpixels,
                                  superpixel_cache_dir) ? 1 : 0;
    if (progress) progress("superpixels", i + 1, todo.size());
  }
  return computed;
}

TileFusionResult FuseTile(const ColmapWorkspace& workspace, const TilePlan& plan, const PlannedTile& tile,
                          const SacOptions& options, const std::string& superpixel_cache_dir, PointSink& sink) {
  const auto& views = workspace.views();
  std::vector<WindowRasters> rasters;
  rasters.reserve(tile.views.size());
  std::vector<SacView> sac_views;
  sac_views.reserve(tile.views.size());
  for (const TileViewWindow& tw : tile.views) {
    const View& view = views[tw.view];
    const DepthRasterSize& size = plan.depth_sizes[tw.view];
    rasters.push_back(LoadWindow(workspace, view, size, tw.window, superpixel_cache_dir));
    WindowRasters& r = rasters.back();
    SacView sv;
    sv.view = view;
    sv.depth = &r.depth;
    sv.superpixels = &r.superpixels;
    sv.image = r.image.empty() ? nullptr : &r.image;
    sv.depth_camera = WindowCamera(view.camera.Scaled(size.width, size.height), tw.window);
    sv.world_from_cam = view.cam_from_world.Inverse();
    sac_views.push_back(sv);
  }
  CoreFilterSink core_sink(plan.grid, tile.index, sink);
  TileFusionResult result;
  result.stats = RunSacFusion(sac_views, options, core_sink);
  result.points_in_core = core_sink.inside();
  result.points_outside_core = core_sink.outside();
  return result;
}

}  // namespace sacfuse
