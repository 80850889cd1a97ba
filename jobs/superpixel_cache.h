#pragma once
// Superpixels are computed once per view and stored on disk (io/superpixel_io.h); later runs, and later the
// tiles of one run, reuse them when the options fingerprint and raster size match.
#include <string>

#include "config/job_config.h"
#include "core/raster.h"
#include "core/superpixels.h"

namespace sacfuse {

// The superpixel (and colour) cache folder of a job: fusion.superpixel_cache_dir, or <output.dir>/superpixels.
std::string SuperpixelCacheDir(const JobConfig& config);

// Cache file of an image name ("nadir/0001.jpg" -> "<dir>/nadir/0001.jpg.spx").
std::string SuperpixelCachePath(const std::string& cache_dir, const std::string& image_name);

// Whether a readable cache file exists for this image with the options fingerprint and raster size given.
bool SuperpixelCacheIsCurrent(const std::string& cache_dir, const std::string& image_name, int width, int height,
                              const SuperpixelOptions& options);

// Loads the cached superpixels of a view, or computes and stores them. `*computed` tells which happened.
SuperpixelMap LoadOrComputeSuperpixels(const std::string& cache_dir, const std::string& image_name,
                                       const RgbImage& image, const DepthMap& depth,
                                       const SuperpixelOptions& options, bool* computed = nullptr);

// Colour cache file of an image name ("nadir/0001.jpg" -> "<dir>/nadir/0001.jpg.rgb"): the image resampled to
// the depth raster (io/colour_raster_io.h), written by the superpixel pass so tiles read colour windows.
std::string ColourCachePath(const std::string& cache_dir, const std::string& image_name);

// Whether a readable colour cache of width x height exists for this image.
bool ColourCacheIsCurrent(const std::string& cache_dir, const std::string& image_name, int width, int height);

}  // namespace sacfuse
