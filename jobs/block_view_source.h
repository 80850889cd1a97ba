#pragma once
// The views of a whole block (an untiled run): every view's whole depth map, its colours resampled to the depth
// grid, its superpixels (loaded from the cache folder or computed and stored there) and, when asked for, its
// dense-matching consistency graph.
#include <string>

#include "core/sac_fusion.h"
#include "core/sac_options.h"
#include "jobs/view_source.h"

namespace sacfuse {

class BlockViewSource : public ViewSource {
 public:
  // `superpixels`: the options the superpixels are computed with (and their cache files keyed by).
  // `views_in_flight`: views read and segmented at once (jobs/view_batches.h; SuperpixelViewsInFlight).
  BlockViewSource(const DepthBlock& input, const SuperpixelOptions& superpixels, std::string cache_dir,
                  SacProgress progress = {}, size_t views_in_flight = 1);
  std::unique_ptr<LoadedViews> Load(const FusionNeeds& needs) const override;
  RgbImage LoadColours(const LoadedViews& loaded, size_t i) const override;

 private:
  const DepthBlock& input_;
  SuperpixelOptions superpixel_options_;
  std::string cache_dir_;
  SacProgress progress_;
  size_t views_in_flight_;
};

}  // namespace sacfuse
