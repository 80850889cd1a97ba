#include "jobs/block_view_source.h"

#include <atomic>
#include <chrono>
#include <optional>
#include <utility>

#include "core/colour_resample.h"
#include "core/error.h"
#include "io/view_identity.h"
#include "jobs/superpixel_cache.h"
#include "jobs/view_batches.h"

namespace sacfuse {

BlockViewSource::BlockViewSource(const DepthBlock& input, const SuperpixelOptions& superpixels, std::string cache_dir,
                                 SacProgress progress, size_t views_in_flight)
    : input_(input), superpixel_options_(superpixels), cache_dir_(std::move(cache_dir)),
      progress_(std::move(progress)), views_in_flight_(views_in_flight) {}

std::unique_ptr<LoadedViews> BlockViewSource::Load(const FusionNeeds& needs) const {
  const auto start = std::chrono::steady_clock::now();
  const auto& views = input_.views();
  auto out = std::make_unique<LoadedViews>();
  out->Reserve(views.size());
  std::atomic<size_t> computed_views{0};
  // Each view fills only its own slot of the storage; the views are appended in the block's order below.
  ForEachViewInFlight(views.size(), views_in_flight_, [&](size_t i) {
    const View& view = views[i];
    out->depths[i] = input_.ReadDepthMap(view);
    const DepthMap& depth = out->depths[i];
    // The image is decoded only for what needs it: superpixels not in the cache, colours loaded with the view.
    std::optional<RgbImage> image;
    const auto read_image = [&]() -> const RgbImage& {
      if (!image) image = input_.ReadImage(view);
      return *image;
    };
    if (needs.superpixels) {
      bool computed = false;
      out->superpixels[i] = LoadOrComputeSuperpixels(cache_dir_, view, read_image, depth, superpixel_options_,
                                                     IdentifyView(input_, view), &computed);
      if (computed) ++computed_views;
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
    if (!needs.colours_one_view_at_a_time) {
      read_image();  // the image is not needed after this
      out->colours[i] = ColoursOnDepthGrid(std::move(*image), depth.width, depth.height);
    }
  }, [&](size_t loaded) {
    if (progress_) progress_(needs.superpixels ? "load + superpixels" : "load", loaded, views.size());
  });
  for (size_t i = 0; i < views.size(); ++i) {
    PixelWindow whole;
    whole.row_end = out->depths[i].height;
    whole.col_end = out->depths[i].width;
    out->AddView(static_cast<uint32_t>(i), views[i], {whole.col_end, whole.row_end}, whole, needs, i);
  }
  out->superpixels_computed = computed_views;
  out->load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

RgbImage BlockViewSource::LoadColours(const LoadedViews& loaded, size_t i) const {
  const DepthMap& depth = loaded.depths[i];
  return ColoursOnDepthGrid(input_.ReadImage(input_.views()[loaded.view_ids[i]]), depth.width, depth.height);
}

}  // namespace sacfuse
