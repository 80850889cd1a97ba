#include "jobs/block_view_source.h"

#include <chrono>

#include "core/colour_resample.h"
#include "core/error.h"
#include "io/view_identity.h"
#include "jobs/superpixel_cache.h"

namespace sacfuse {

BlockViewSource::BlockViewSource(const DepthBlock& input, const SuperpixelOptions& superpixels, std::string cache_dir,
                                 SacProgress progress)
    : input_(input), superpixel_options_(superpixels), cache_dir_(std::move(cache_dir)),
      progress_(std::move(progress)) {}

std::unique_ptr<LoadedViews> BlockViewSource::Load(const FusionNeeds& needs) const {
  const auto start = std::chrono::steady_clock::now();
  const auto& views = input_.views();
  auto out = std::make_unique<LoadedViews>();
  out->Reserve(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    const View& view = views[i];
    out->depths[i] = input_.ReadDepthMap(view);
    const DepthMap& depth = out->depths[i];
    const RgbImage image = input_.ReadImage(view);
    if (needs.superpixels) {
      bool computed = false;
      out->superpixels[i] =
          LoadOrComputeSuperpixels(cache_dir_, view, image, depth, superpixel_options_, IdentifyView(input_, view),
                                   &computed);
      out->superpixels_computed += computed ? 1 : 0;
    }
    if (needs.consistency_graphs) {
      if (!input_.HasConsistencyGraph(view)) {
        throw InputError(input_.source(),
                         "fusion.correspondence = dense needs the dense matcher's consistency graphs, and image " +
                             view.name + " has none (COLMAP: --PatchMatchStereo.write_consistency_graph 1, in "
                             "stereo/consistency_graphs/); use reprojection or proximity");
      }
      out->graphs[i] = input_.ReadConsistencyGraph(view);
    }
    out->colours[i] = ResampleColourToDepthGrid(image, depth.width, depth.height);
    PixelWindow whole;
    whole.row_end = depth.height;
    whole.col_end = depth.width;
    out->AddView(static_cast<uint32_t>(i), view, {depth.width, depth.height}, whole, needs, i);
    if (progress_) progress_(needs.superpixels ? "load + superpixels" : "load", i + 1, views.size());
  }
  out->load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace sacfuse
