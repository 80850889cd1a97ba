#include "jobs/tiled_sac.h"

#include <algorithm>
#include <filesystem>
#include <vector>


#include "core/error.h"
#include "core/colour_resample.h"
#include "io/colour_raster_io.h"
#include "io/superpixel_io.h"
#include "jobs/fusion_methods.h"
#include "jobs/method_geometry.h"
#include "jobs/superpixel_cache.h"

namespace sacfuse {
namespace {

// Computes and caches a view's superpixels (when `with_superpixels`) and its colours on the depth grid unless
// those caches exist (then nothing is read).
bool EnsureViewCaches(const DepthBlock& input, const View& view, const DepthRasterSize& size,
                      const SuperpixelOptions& options, const std::string& cache_dir, bool with_superpixels) {
  const bool spx_ok =
      !with_superpixels || SuperpixelCacheIsCurrent(cache_dir, view.name, size.width, size.height, options);
  const bool rgb_ok = ColourCacheIsCurrent(cache_dir, view.name, size.width, size.height);
  if (spx_ok && rgb_ok) return false;
  const RgbImage image = input.ReadImage(view);
  if (!with_superpixels) {  // colours only: no depth needed
    if (!image.empty()) {
      WriteColourRaster(ColourCachePath(cache_dir, view.name), ResampleColourToDepthGrid(image, size.width, size.height));
    }
    return false;
  }
  const DepthMap depth = input.ReadDepthMap(view);
  bool computed = false;
  if (!spx_ok) LoadOrComputeSuperpixels(cache_dir, view.name, image, depth, options, &computed);
  if (!rgb_ok && !image.empty()) {
    WriteColourRaster(ColourCachePath(cache_dir, view.name), ResampleColourToDepthGrid(image, size.width, size.height));
  }
  return computed;
}

// The superpixels of a window: the clusters its labels use, renumbered 0.. in ascending order of their index in
// the view (so nodes keep the untiled order), with centroids in window coordinates. Cluster statistics are the
// whole view's, so a cluster whose centroid lies in the window becomes the same node as in an untiled run.
SuperpixelMap WindowSuperpixels(std::vector<int32_t> labels, const std::vector<SuperpixelCluster>& view_clusters,
                                const PixelWindow& w) {
  std::vector<int32_t> local(view_clusters.size(), -1);
  for (const int32_t l : labels) local[static_cast<size_t>(l)] = 0;
  SuperpixelMap out;
  out.width = w.width();
  out.height = w.height();
  for (size_t c = 0; c < local.size(); ++c) {
    if (local[c] < 0) continue;
    local[c] = static_cast<int32_t>(out.clusters.size());
    SuperpixelCluster cluster = view_clusters[c];
    cluster.centroid_col -= static_cast<float>(w.col_begin);
    cluster.centroid_row -= static_cast<float>(w.row_begin);
    out.clusters.push_back(cluster);
  }
  for (int32_t& l : labels) l = local[static_cast<size_t>(l)];
  out.labels = std::move(labels);
  return out;
}

// The rasters of one view inside one tile, owned here; SacView points into them.
struct WindowRasters {
  DepthMap depth;
  SuperpixelMap superpixels;
  RgbImage image;  // at depth-window resolution; empty = no colours
};

// The colours of a window from the colour cache (empty when the view has none).
RgbImage LoadWindowColours(const View& view, const PixelWindow& w, const std::string& cache_dir) {
  const std::string rgb_path = ColourCachePath(cache_dir, view.name);
  return std::filesystem::exists(rgb_path) ? ReadColourRasterWindow(rgb_path, w) : RgbImage{};
}

WindowRasters LoadWindow(const DepthBlock& input, const View& view, const DepthRasterSize& size,
                         const PixelWindow& w, const std::string& cache_dir, ClusterTableCache* cluster_cache) {
  WindowRasters out;
  out.depth = input.ReadDepthWindow(view, w);
  const std::string spx_path = SuperpixelCachePath(cache_dir, view.name);
  SuperpixelFileInfo info;
  std::vector<int32_t> labels = ReadSuperpixelLabelWindow(spx_path, w, &info);
  if (info.width != size.width || info.height != size.height) {
    throw InputError(spx_path, "superpixel raster is not the depth map's size");
  }
  std::shared_ptr<const std::vector<SuperpixelCluster>> clusters =
      cluster_cache != nullptr ? cluster_cache->Get(spx_path)
                               : std::make_shared<const std::vector<SuperpixelCluster>>(ReadSuperpixelClusters(spx_path));
  out.superpixels = WindowSuperpixels(std::move(labels), *clusters, w);
  out.image = LoadWindowColours(view, w, cache_dir);
  return out;
}

// Forwards every point, counting them.
class CountingSink : public PointSink {
 public:
  explicit CountingSink(PointSink& next) : next_(next) {}
  void Write(const FusedPoint* points, size_t count) override {
    count_ += count;
    next_.Write(points, count);
  }
  uint64_t count() const { return count_; }

 private:
  PointSink& next_;
  uint64_t count_ = 0;
};

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

size_t EnsureTiledSuperpixels(const DepthBlock& input, const TilePlan& plan, const SacOptions& options,
                              const std::string& superpixel_cache_dir, const SacProgress& progress,
                              const PlannedTile* only_tile, bool with_superpixels) {
  const auto& views = input.views();
  std::vector<size_t> todo;
  if (only_tile == nullptr) {
    for (size_t v = 0; v < views.size(); ++v) todo.push_back(v);
  } else {
    for (const TileViewWindow& tw : only_tile->views) todo.push_back(tw.view);
  }
  size_t computed = 0;
  for (size_t i = 0; i < todo.size(); ++i) {
    const size_t v = todo[i];
    computed += EnsureViewCaches(input, views[v], plan.depth_sizes[v], options.superpixels, superpixel_cache_dir,
                                 with_superpixels) ? 1 : 0;
    if (progress) progress("superpixels", i + 1, todo.size());
  }
  return computed;
}

namespace {

// A comparison method (jobs/fusion_methods.h) on one tile: depth and colour windows only, the block's neighbour
// views and order restricted to the tile's views.
TileFusionResult FuseTileWithMethod(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile,
                                    const FusionOptions& fusion, const std::string& cache_dir, PointSink& sink) {
  const auto& views = input.views();
  std::vector<DepthMap> depths(tile.views.size());
  std::vector<RgbImage> colours(tile.views.size());
  std::vector<SacView> sac_views;
  std::vector<uint32_t> ids;
  for (size_t i = 0; i < tile.views.size(); ++i) {
    const TileViewWindow& tw = tile.views[i];
    const View& view = views[tw.view];
    depths[i] = input.ReadDepthWindow(view, tw.window);
    colours[i] = LoadWindowColours(view, tw.window, cache_dir);
    SacView sv;
    sv.view = view;
    sv.depth = &depths[i];
    sv.image = colours[i].empty() ? nullptr : &colours[i];
    sv.depth_camera = WindowCamera(view.camera.Scaled(plan.depth_sizes[tw.view].width,
                                                      plan.depth_sizes[tw.view].height), tw.window);
    sv.world_from_cam = view.cam_from_world.Inverse();
    sac_views.push_back(sv);
    ids.push_back(tw.view);
  }
  const MethodGeometry geometry =
      BlockMethodGeometry(input, plan.depth_sizes, plan.z_min_m, plan.z_max_m, NeighborOptionsOf(fusion.sac));
  CoreFilterSink core_sink(plan.grid, tile.index, sink);
  FootprintBox halo;
  halo.Extend(tile.halo.min);
  halo.Extend(tile.halo.max);
  TileFusionResult result;
  result.method_stats = RunFusionMethod(fusion, sac_views, SubsetViewPlan(geometry.plan, ids), geometry.gsd_m,
                                        core_sink, &halo);
  result.points_in_core = core_sink.inside();
  result.points_outside_core = core_sink.outside();
  // Input counts of the core only (each pixel of the block then counts in exactly one tile).
  MethodStats& stats = result.method_stats;
  stats.input_pixels = 0;
  stats.input_per_view.assign(sac_views.size(), 0);
  for (size_t i = 0; i < sac_views.size(); ++i) {
    const DepthMap& d = depths[i];
    for (int row = 0; row < d.height; ++row) {
      for (int col = 0; col < d.width; ++col) {
        if (!IsValidDepth(d.at(row, col))) continue;
        const Eigen::Vector3d p = PixelPoint(sac_views[i], row, col, d.at(row, col));
        if (plan.grid.TileOf(p.x(), p.y()) == tile.index) ++stats.input_per_view[i];
      }
    }
    stats.input_pixels += stats.input_per_view[i];
  }
  return result;
}

}  // namespace

TileFusionResult FuseTile(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile,
                          const FusionOptions& fusion, const std::string& superpixel_cache_dir, PointSink& sink,
                          ClusterTableCache* cluster_cache) {
  if (fusion.method != "sac") return FuseTileWithMethod(input, plan, tile, fusion, superpixel_cache_dir, sink);
  const SacOptions& options = fusion.sac;
  const auto& views = input.views();
  std::vector<WindowRasters> rasters;
  rasters.reserve(tile.views.size());
  std::vector<SacView> sac_views;
  sac_views.reserve(tile.views.size());
  for (const TileViewWindow& tw : tile.views) {
    const View& view = views[tw.view];
    const DepthRasterSize& size = plan.depth_sizes[tw.view];
    rasters.push_back(LoadWindow(input, view, size, tw.window, superpixel_cache_dir, cluster_cache));
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
  // Pixels are owned by the tile core their own point falls in (before SAC's averaging moves it a little along
  // its ray, differently in each tile), so each is emitted by exactly one tile.
  const TileGrid& grid = plan.grid;
  const TileIndex index = tile.index;
  CountingSink counted(sink);
  TileFusionResult result;
  result.stats = RunSacFusion(sac_views, options, counted, {},
                              [&](const Eigen::Vector3d& p) { return grid.TileOf(p.x(), p.y()) == index; });
  result.points_in_core = counted.count();
  result.points_outside_core = result.stats.collapse.not_owned;
  return result;
}

}  // namespace sacfuse
