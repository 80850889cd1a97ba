#include "jobs/superpixel_cache.h"

#include <filesystem>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "io/superpixel_io.h"

namespace sacfuse {

std::string SuperpixelCachePath(const std::string& cache_dir, const std::string& image_name) {
  return (std::filesystem::path(cache_dir) / (image_name + ".spx")).string();
}

SuperpixelMap LoadOrComputeSuperpixels(const std::string& cache_dir, const std::string& image_name,
                                       const RgbImage& image, const DepthMap& depth,
                                       const SuperpixelOptions& options, bool* computed) {
  const std::string path = SuperpixelCachePath(cache_dir, image_name);
  const uint64_t hash = SuperpixelOptionsHash(options);
  if (std::filesystem::exists(path)) {
    try {
      const SuperpixelFileInfo info = ReadSuperpixelInfo(path);
      if (info.options_hash == hash && info.width == depth.width && info.height == depth.height) {
        if (computed != nullptr) *computed = false;
        return ReadSuperpixels(path);
      }
      spdlog::info("superpixels of {} are stale (options or size changed); recomputing", image_name);
    } catch (const Error& e) {
      spdlog::warn("ignoring unreadable superpixel cache {}: {}", path, e.what());
    }
  }
  SuperpixelMap map = ComputeSuperpixels(image, depth, options);
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteSuperpixels(path, map, hash);
  if (computed != nullptr) *computed = true;
  return map;
}

}  // namespace sacfuse
