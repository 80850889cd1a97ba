#pragma once
// Superpixels are computed once per view and stored on disk (io/superpixel_io.h); later runs, and later the
// tiles of one run, reuse them when the options fingerprint and raster size match and the view's inputs are the
// ones they were made from. Beside each cache file, "<image>.inputs-spx.json" / ".inputs-rgb.json" records the view's identity
// (io/view_identity.h) when the file was written and the identity of the cache file itself: a cache is current
// only when the inputs it depends on (superpixels: depth map and image; colours: image) are unchanged and the
// file is the one written then (a cache file edited, truncated or replaced afterwards is recomputed).
#include <functional>
#include <string>

#include "config/job_config.h"
#include "config/output_layout.h"
#include "core/raster.h"
#include "core/superpixels.h"
#include "core/view.h"
#include "io/view_identity.h"

namespace sacfuse {

// The cache folder and file names: SuperpixelCacheDir, SuperpixelCachePath, ColourCachePath (config/output_layout.h).

// Whether a cache is current, and why not.
struct CacheCheck {
  bool current = false;
  bool inputs_changed = false;  // not current because the view's inputs changed (reason says how)
  std::string reason;           // "" when current, or when there is simply no cache yet
};

// The superpixel cache of `view` against the options fingerprint, raster size and the view's `inputs`.
CacheCheck CheckSuperpixelCache(const std::string& cache_dir, const View& view, int width, int height,
                                const SuperpixelOptions& options, const ViewIdentity& inputs);

// Loads the cached superpixels of a view, or computes and stores them (with their input record). A cache whose
// inputs changed is recomputed and the change logged; one that cannot be read (a corrupt body) is recomputed
// with a warning. `*computed` tells which happened. `image` gives the view's image, asked only when computing.
// `packing`: how computed labels are held (LabelPacking::kUnpacked where the map is only cached and dropped).
SuperpixelMap LoadOrComputeSuperpixels(const std::string& cache_dir, const View& view,
                                       const std::function<const RgbImage&()>& image,
                                       const DepthMap& depth, const SuperpixelOptions& options,
                                       const ViewIdentity& inputs, bool* computed = nullptr,
                                       LabelPacking packing = LabelPacking::kPacked);

// The colour cache of `view` against the raster size and the view's image identity.
CacheCheck CheckColourCache(const std::string& cache_dir, const View& view, int width, int height,
                            const ViewIdentity& inputs);
// Writes the colour cache of `view` (`colours` on its depth grid) and its input record.
void WriteColourCache(const std::string& cache_dir, const View& view, const RgbImage& colours,
                      const ViewIdentity& inputs);

// Logs why a cache is not current (an input change at info, a damaged cache as a warning) naming the view.
void LogCacheCheck(const CacheCheck& check, const View& view, const char* what);

}  // namespace sacfuse
