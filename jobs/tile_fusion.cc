#include "jobs/tile_fusion.h"

#include <atomic>
#include <utility>
#include <vector>

#include "core/colour_resample.h"
#include "io/colour_raster_io.h"
#include "jobs/fusion_methods.h"
#include "jobs/method_geometry.h"
#include "jobs/method_memory.h"
#include "jobs/superpixel_cache.h"
#include "jobs/tile_view_source.h"
#include "jobs/view_batches.h"

namespace sacfuse {
namespace {

// Computes and caches a view's superpixels (when `with_superpixels`) and its colours on the depth grid unless
// those caches are current for the view's `inputs` (then nothing is read).
bool EnsureViewCaches(const DepthBlock& input, const View& view, const DepthRasterSize& size,
                      const SuperpixelOptions& options, const std::string& cache_dir, bool with_superpixels,
                      const ViewIdentity& inputs) {
  const CacheCheck spx = with_superpixels
                             ? CheckSuperpixelCache(cache_dir, view, size.width, size.height, options, inputs)
                             : CacheCheck{true, false, ""};
  const CacheCheck rgb = CheckColourCache(cache_dir, view, size.width, size.height, inputs);
  if (spx.current && rgb.current) return false;
  if (!rgb.current && (spx.current || spx.reason != rgb.reason)) LogCacheCheck(rgb, view, "colours");
  RgbImage image = input.ReadImage(view);
  bool computed = false;
  if (!spx.current) {
    const DepthMap depth = input.ReadDepthMap(view);
    // The map is written to the cache and dropped: its labels are not packed (LabelPacking).
    LoadOrComputeSuperpixels(cache_dir, view, [&]() -> const RgbImage& { return image; }, depth, options, inputs,
                             &computed, LabelPacking::kUnpacked);
  }
  // Last, so that the image can be handed over (ColoursOnDepthGrid).
  if (!rgb.current && !image.empty()) {
    WriteColourCache(cache_dir, view, ColoursOnDepthGrid(std::move(image), size.width, size.height), inputs);
  }
  return computed;
}

}  // namespace

size_t EnsureTiledSuperpixels(const DepthBlock& input, const TilePlan& plan, const SacOptions& options,
                              const std::string& superpixel_cache_dir, const std::vector<ViewIdentity>& inputs,
                              const SacProgress& progress, const PlannedTile* only_tile, bool with_superpixels,
                              size_t views_in_flight) {
  const auto& views = input.views();
  std::vector<size_t> todo;
  if (only_tile == nullptr) {
    for (size_t v = 0; v < views.size(); ++v) todo.push_back(v);
  } else {
    for (const TileViewWindow& tw : only_tile->views) todo.push_back(tw.view);
  }
  std::atomic<size_t> computed{0};
  ForEachViewInFlight(todo.size(), views_in_flight, [&](size_t i) {
    const size_t v = todo[i];
    if (EnsureViewCaches(input, views[v], plan.depth_sizes[v], options.superpixels, superpixel_cache_dir,
                         with_superpixels, inputs.at(v))) {
      ++computed;
    }
  }, [&](size_t done) {
    if (progress) progress("superpixels", done, todo.size());
  });
  return computed;
}

FusedViews FuseTile(const DepthBlock& input, const TilePlan& plan, const PlannedTile& tile,
                    const FusionOptions& fusion, const std::string& superpixel_cache_dir, PointSink& sink,
                    ClusterTableCache* cluster_cache) {
  const std::unique_ptr<FusionMethod> method = MakeFusionMethod(fusion);
  MethodGeometry geometry;
  if (method->needs().block_geometry) {
    geometry = BlockMethodGeometry(input, plan.depth_sizes, plan.z_min_m, plan.z_max_m, NeighborOptionsOf(fusion.sac));
  }
  Box2d halo;
  halo.Extend(tile.halo.min);
  halo.Extend(tile.halo.max);
  FusionScope scope;
  scope.region_xy = &halo;
  scope.owns = plan.grid.OwnedRegionOf(tile.index);
  const TileViewSource source(input, plan, tile, superpixel_cache_dir, cluster_cache);
  return FuseViews(*method, source, &geometry, std::move(scope), sink);
}

MethodTileFuser::MethodTileFuser(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                                 const std::vector<ViewIdentity>& identities, ClusterTableCache* cluster_cache)
    : config_(config),
      input_(input),
      plan_(plan),
      identities_(identities),
      cluster_cache_(cluster_cache),
      fusion_(WithTsdfMemoryLimit(config)),
      cache_dir_(SuperpixelCacheDir(config)) {}

uint64_t MethodTileFuser::TileBytes(const PlannedTile& tile) const { return MethodTileBytes(tile, config_.fusion); }

void MethodTileFuser::PrepareTile(const PlannedTile& tile) {
  const bool superpixels = MakeFusionMethod(config_.fusion)->needs().superpixels;
  EnsureTiledSuperpixels(input_, plan_, config_.fusion.sac, cache_dir_, identities_, {}, &tile, superpixels);
}

TileFused MethodTileFuser::Fuse(const PlannedTile& tile, PointSink& sink) {
  FusedViews fused = FuseTile(input_, plan_, tile, fusion_, cache_dir_, sink, cluster_cache_);
  TileFused out;
  out.stats = std::move(fused.stats);
  out.view_ids = std::move(fused.view_ids);
  out.points_written = fused.points_written;
  out.points_per_view = std::move(fused.points_per_view);
  out.points_not_owned = fused.points_not_owned;
  return out;
}

}  // namespace sacfuse
