#include "jobs/method_block.h"

#include <chrono>
#include <string>

#include <spdlog/spdlog.h>

#include "core/colour_resample.h"
#include "jobs/fusion_methods.h"
#include "jobs/method_geometry.h"
#include "jobs/method_memory.h"
#include "jobs/tile_plan.h"

namespace sacfuse {

MethodBlockResult FuseWorkspaceWithMethod(const DepthBlock& input, const JobConfig& config, PointSink& sink,
                                          const SacProgress& progress) {
  const auto& views = input.views();
  MethodBlockResult result;
  const auto start = std::chrono::steady_clock::now();
  std::vector<DepthMap> depths(views.size());
  std::vector<RgbImage> colours(views.size());
  std::vector<DepthRasterSize> sizes(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    depths[i] = input.ReadDepthMap(views[i]);
    sizes[i] = {depths[i].width, depths[i].height};
    colours[i] = ResampleColourToDepthGrid(input.ReadImage(views[i]), depths[i].width, depths[i].height);
    if (progress) progress("load", i + 1, views.size());
  }
  result.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double z_min = 0, z_max = 0;
  std::string z_source;
  BlockHeightRange(input.SceneHeights(), config.tiling, &z_min, &z_max, &z_source);
  const MethodGeometry geometry =
      BlockMethodGeometry(input, sizes, z_min, z_max, NeighborOptionsOf(config.fusion.sac));
  spdlog::info("{}: {} views loaded in {:.1f} s; block GSD {:.3f} m from the geometry (heights [{:.1f}, {:.1f}] m "
               "from {})",
               config.fusion.method, views.size(), result.load_seconds, geometry.gsd_m, z_min, z_max, z_source);
  std::vector<SacView> sac_views;
  sac_views.reserve(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    sac_views.push_back(MakeSacView(views[i], &depths[i], nullptr, colours[i].empty() ? nullptr : &colours[i]));
  }
  result.stats = RunFusionMethod(WithTsdfMemoryLimit(config), sac_views, geometry.plan, geometry.gsd_m, sink);
  return result;
}

}  // namespace sacfuse
