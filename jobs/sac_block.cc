#include "jobs/sac_block.h"

#include <chrono>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "jobs/superpixel_cache.h"

namespace sacfuse {

SacBlockResult FuseWorkspaceWithSac(const DepthBlock& input, const SacOptions& options,
                                    const std::string& superpixel_cache_dir, PointSink& sink,
                                    const SacProgress& progress) {
  ValidateSacOptions(options);
  const auto& views = input.views();
  std::vector<DepthMap> depths(views.size());
  std::vector<RgbImage> images(views.size());
  std::vector<SuperpixelMap> superpixels(views.size());
  std::vector<ConsistencyGraph> graphs(views.size());
  const bool dense = options.correspondence == "dense";
  SacBlockResult result;
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < views.size(); ++i) {
    depths[i] = input.ReadDepthMap(views[i]);
    images[i] = input.ReadImage(views[i]);
    bool computed = false;
    superpixels[i] = LoadOrComputeSuperpixels(superpixel_cache_dir, views[i].name, images[i], depths[i],
                                              options.superpixels, &computed);
    result.superpixels_computed += computed ? 1 : 0;
    if (dense) {
      if (!input.HasConsistencyGraph(views[i])) {
        throw InputError(input.source(),
                         "fusion.correspondence = dense needs the dense matcher's consistency graphs, and image " +
                             views[i].name + " has none (COLMAP: --PatchMatchStereo.write_consistency_graph 1, in "
                             "stereo/consistency_graphs/); use reprojection or proximity");
      }
      graphs[i] = input.ReadConsistencyGraph(views[i]);
    }
    if (progress) progress("load + superpixels", i + 1, views.size());
  }
  result.superpixel_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("superpixels: {} computed, {} reused from {} ({:.1f} s with loading)", result.superpixels_computed,
               views.size() - result.superpixels_computed, superpixel_cache_dir, result.superpixel_seconds);
  std::vector<SacView> sac_views;
  sac_views.reserve(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    sac_views.push_back(MakeSacView(views[i], &depths[i], &superpixels[i], &images[i], dense ? &graphs[i] : nullptr));
  }
  result.stats = RunSacFusion(sac_views, options, sink, progress);
  return result;
}

}  // namespace sacfuse
