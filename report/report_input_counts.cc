#include "report/report_input_counts.h"

#include <algorithm>
#include <filesystem>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "io/superpixel_io.h"
#include "config/output_layout.h"

namespace sacfuse {
namespace {

// Sum of the clusters' valid counts when the view's cache file is readable and of the raster's size.
bool ValidPixelsFromCache(const std::string& path, const DepthRasterSize& size, uint64_t* count) {
  if (!std::filesystem::exists(path)) return false;
  try {
    const SuperpixelFileInfo info = ReadSuperpixelInfo(path);
    if (info.width != size.width || info.height != size.height) return false;
    uint64_t sum = 0;
    for (const SuperpixelCluster& c : ReadSuperpixelClusters(path)) sum += c.valid_count;
    *count = sum;
    return true;
  } catch (const Error& e) {
    spdlog::warn("superpixel cache {} unreadable ({}); counting valid depth pixels from the depth map", path,
                 e.what());
    return false;
  }
}

}  // namespace

uint64_t CountValidDepthPixels(const DepthBlock& input, const View& view) {
  const DepthRasterSize size = input.DepthSize(view);
  uint64_t count = 0;
  for (int row = 0; row < size.height; row += kValidPixelCountBandRows) {
    const PixelWindow band{row, std::min(size.height, row + kValidPixelCountBandRows), 0, size.width};
    const DepthMap depth = input.ReadDepthWindow(view, band);
    for (const float d : depth.data) count += IsValidDepth(d) ? 1 : 0;
  }
  return count;
}

std::vector<uint64_t> ValidDepthPixelsPerView(const DepthBlock& input, const std::string& superpixel_cache_dir,
                                              size_t* not_cached, bool count_rasters) {
  const auto& views = input.views();
  std::vector<uint64_t> counts(views.size(), 0);
  size_t missing = 0;
  for (size_t i = 0; i < views.size(); ++i) {
    const DepthRasterSize size = input.DepthSize(views[i]);
    if (!ValidPixelsFromCache(SuperpixelCachePath(superpixel_cache_dir, views[i].name), size, &counts[i])) {
      if (count_rasters) counts[i] = CountValidDepthPixels(input, views[i]);
      ++missing;
    }
  }
  if (missing > 0 && count_rasters) {
    spdlog::info("valid depth pixels: {} of {} views counted from their depth maps (no superpixel cache)", missing,
                 views.size());
  }
  if (not_cached != nullptr) *not_cached = missing;
  return counts;
}

}  // namespace sacfuse
