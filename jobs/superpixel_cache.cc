#include "jobs/superpixel_cache.h"

#include <filesystem>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "io/colour_raster_io.h"
#include "io/superpixel_io.h"

namespace sacfuse {

std::string SuperpixelCacheDir(const JobConfig& config) {
  return config.fusion.superpixel_cache_dir.empty()
             ? (std::filesystem::path(config.output.dir) / "superpixels").string()
             : config.fusion.superpixel_cache_dir;
}

std::string SuperpixelCachePath(const std::string& cache_dir, const std::string& image_name) {
  return (std::filesystem::path(cache_dir) / (image_name + ".spx")).string();
}

bool SuperpixelCacheIsCurrent(const std::string& cache_dir, const std::string& image_name, int width, int height,
                              const SuperpixelOptions& options) {
  const std::string path = SuperpixelCachePath(cache_dir, image_name);
  if (!std::filesystem::exists(path)) return false;
  try {
    const SuperpixelFileInfo info = ReadSuperpixelInfo(path);
    return info.options_hash == SuperpixelOptionsHash(options) && info.width == width && info.height == height;
  } catch (const Error& e) {
    spdlog::warn("ignoring unreadable superpixel cache {}: {}", path, e.what());
    return false;
  }
}

SuperpixelMap LoadOrComputeSuperpixels(const std::string& cache_dir, const std::string& image_name,
                                       const RgbImage& image, const DepthMap& depth,
                                       const SuperpixelOptions& options, bool* computed) {
  const std::string path = SuperpixelCachePath(cache_dir, image_name);
  if (SuperpixelCacheIsCurrent(cache_dir, image_name, depth.width, depth.height, options)) {
    if (computed != nullptr) *computed = false;
    return ReadSuperpixels(path);
  }
  SuperpixelMap map = ComputeSuperpixels(image, depth, options);
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteSuperpixels(path, map, SuperpixelOptionsHash(options));
  if (computed != nullptr) *computed = true;
  return map;
}

std::string ColourCachePath(const std::string& cache_dir, const std::string& image_name) {
  return (std::filesystem::path(cache_dir) / (image_name + ".rgb")).string();
}

bool ColourCacheIsCurrent(const std::string& cache_dir, const std::string& image_name, int width, int height) {
  const std::string path = ColourCachePath(cache_dir, image_name);
  if (!std::filesystem::exists(path)) return false;
  try {
    const ColourRasterInfo info = ReadColourRasterInfo(path);
    return info.width == width && info.height == height;
  } catch (const Error& e) {
    spdlog::warn("ignoring unreadable colour cache {}: {}", path, e.what());
    return false;
  }
}

}  // namespace sacfuse
