#include "jobs/tile_view_source.h"

#include <chrono>
#include <filesystem>

#include "core/error.h"
#include "io/colour_raster_io.h"
#include "io/superpixel_io.h"
#include "jobs/superpixel_cache.h"

namespace sacfuse {
namespace {

// The superpixels of a window: the clusters its labels use, renumbered 0.. in ascending order of their index in
// the view (so nodes keep the untiled order), with centroids in window coordinates.
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
  out.labels = SuperpixelLabels(out.width, out.height, labels);
  return out;
}

SuperpixelMap LoadWindowSuperpixels(const View& view, const DepthRasterSize& size, const PixelWindow& w,
                                    const std::string& cache_dir, ClusterTableCache* cluster_cache) {
  const std::string spx_path = SuperpixelCachePath(cache_dir, view.name);
  SuperpixelFileInfo info;
  std::vector<int32_t> labels = ReadSuperpixelLabelWindow(spx_path, w, &info);
  if (info.width != size.width || info.height != size.height) {
    throw InputError(spx_path, "superpixel raster is not the depth map's size");
  }
  std::shared_ptr<const std::vector<SuperpixelCluster>> clusters =
      cluster_cache != nullptr ? cluster_cache->Get(spx_path)
                               : std::make_shared<const std::vector<SuperpixelCluster>>(ReadSuperpixelClusters(spx_path));
  return WindowSuperpixels(std::move(labels), *clusters, w);
}

// The colours of a window from the colour cache (empty when the view has none).
RgbImage LoadWindowColours(const View& view, const PixelWindow& w, const std::string& cache_dir) {
  const std::string rgb_path = ColourCachePath(cache_dir, view.name);
  return std::filesystem::exists(rgb_path) ? ReadColourRasterWindow(rgb_path, w) : RgbImage{};
}

}  // namespace

TileViewSource::TileViewSource(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile,
                               std::string cache_dir, ClusterTableCache* cluster_cache)
    : input_(input), plan_(plan), tile_(tile), cache_dir_(std::move(cache_dir)), cluster_cache_(cluster_cache) {}

std::unique_ptr<LoadedViews> TileViewSource::Load(const FusionNeeds& needs) const {
  if (needs.consistency_graphs) {
    throw ConfigError("fusion.correspondence = dense: not supported by tiled runs yet");
  }
  const auto start = std::chrono::steady_clock::now();
  const auto& views = input_.views();
  auto out = std::make_unique<LoadedViews>();
  out->Reserve(tile_.views.size());
  for (size_t i = 0; i < tile_.views.size(); ++i) {
    const TileViewWindow& tw = tile_.views[i];
    const View& view = views[tw.view];
    const DepthRasterSize& size = plan_.depth_sizes[tw.view];
    out->depths[i] = input_.ReadDepthWindow(view, tw.window);
    if (needs.superpixels) {
      out->superpixels[i] = LoadWindowSuperpixels(view, size, tw.window, cache_dir_, cluster_cache_);
    }
    if (!needs.colours_one_view_at_a_time) out->colours[i] = LoadColours(*out, i);
    out->AddView(tw.view, view, size, tw.window, needs, i);
  }
  out->load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

RgbImage TileViewSource::LoadColours(const LoadedViews&, size_t i) const {
  const TileViewWindow& tw = tile_.views[i];
  return LoadWindowColours(input_.views()[tw.view], tw.window, cache_dir_);
}

}  // namespace sacfuse
