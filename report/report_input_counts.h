#pragma once
// The "before fusion" count of each view: its valid depth pixels (run_report.json `views[i].input_pixels`, the
// paper's Fig. 4 "before" bars).
//
// SAC runs (untiled and tiled) never hold every view's whole depth map at the end, so the count comes from the
// superpixel cache: superpixels are computed on each view's whole depth raster and every cluster of the cache
// file stores its valid-depth pixel count (io/superpixel_io.h), so the sum over a view's clusters is the view's
// valid depth pixels, read from the cluster table alone (20 bytes per cluster). The count does not depend on the
// superpixel options, only on the depth raster, so any cache file of the raster's size serves. A view without a
// readable cache file of its raster's size is counted from its depth raster itself, read in row bands (bounded
// memory).
#include <cstdint>
#include <string>
#include <vector>

#include "io/depth_block.h"

namespace sacfuse {

// Rows of a depth raster read at once when counting from the raster itself.
constexpr int kValidPixelCountBandRows = 256;

// Valid depth pixels (IsValidDepth) of one view, counted from its depth raster in row bands.
uint64_t CountValidDepthPixels(const DepthBlock& input, const View& view);

// Valid depth pixels of every view of `input` (indexed like input.views()), from the superpixel cluster tables
// in `superpixel_cache_dir` where current (see above), else from the depth raster (or 0 when
// `count_rasters` is false: the cheap variant for a report). *not_cached (optional) receives how many views had
// no usable cache file. Throws InputError for an unreadable depth raster.
std::vector<uint64_t> ValidDepthPixelsPerView(const DepthBlock& input, const std::string& superpixel_cache_dir,
                                              size_t* not_cached = nullptr, bool count_rasters = true);

}  // namespace sacfuse
