#pragma once
// The `--depth sgbm` pass of `sacfuse simulate` over a written workspace: once every image is rendered and the
// sparse model (WRITTEN poses, sparse points with tracks) is complete, each view's depth map is matched from the
// JPEG images on disk (tools/sim/sgbm_depth.h) and handed to `write_maps`; its error against the true depth
// (`true_depth`, the rendered depth of the same pixel grid) is recorded. Grey images are decoded on demand and a
// few are kept (views are visited in order and match their neighbours).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/raster.h"
#include "io/colmap_model.h"
#include "tools/sim/sgbm_options.h"

namespace sacfuse::sim {

struct SgbmViewReport {
  std::string name;
  std::vector<std::string> sources;
  std::vector<double> pair_valid_fraction;
  double valid_fraction = 0.0;         // merged
  double median_abs_error_m = 0.0;     // against the true depth, over pixels valid in both
  double p90_abs_error_m = 0.0;
  double share_over_1m = 0.0;          // of those pixels, off by more than 1 m
  double seconds = 0.0;
};

struct SgbmPassSummary {
  std::vector<SgbmViewReport> views;   // in the model's images order
  uint64_t valid_pixels = 0;
  size_t pairs = 0;
  double match_seconds = 0.0;          // StereoSGBM alone
  double seconds = 0.0;                // the whole pass
};

struct SgbmPassIo {
  std::string images_dir;              // images/<name>
  int depth_downsample = 1;            // depth raster = image size / this (images are resized to it)
  std::function<DepthMap(uint32_t image_index)> true_depth;   // may be empty: no error statistics
  std::function<void(uint32_t image_index, const DepthMap& depth)> write_maps;
  std::function<void(size_t done, size_t total)> progress;    // may be empty
};

// Throws Error naming the image when one cannot be read.
SgbmPassSummary RunSgbmPass(const ColmapModel& model, const SgbmDepthOptions& options, const SgbmPassIo& io);

}  // namespace sacfuse::sim
