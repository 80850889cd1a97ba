#pragma once
// SLIC superpixel clusters of one view: the graph nodes of SAC fusion (paper section III.C). Each cluster is
// represented by its centroid and a robust depth; all pixels of a cluster later inherit the cluster's label.
//
// Segmentation runs on the depth raster's grid: the colour image is resampled to it, converted to 8-bit CIE Lab
// (OpenCV convention: L*255/100, a+128, b+128, so one unit ~ 0.4 L* ~ 1 a*/b*) and clustered with
// cv::ximgproc SLIC / SLICO / MSLIC, followed by OpenCV's connectivity enforcement (fragments below 1/4 of a
// region are merged into a neighbour), or with our own SLIC (`fast`, core/slic_fast.h: same Lab input and
// depth channel, same 1/4-region fragment rule, several times faster).
#include <cstdint>
#include <string>
#include <vector>

#include "core/raster.h"
#include "core/superpixel_labels.h"

namespace sacfuse {

struct SuperpixelOptions {
  int region_size_px = 16;  // SLIC region size (seed spacing), pixels of the depth raster. [2, 128]
  // SLIC compactness (OpenCV "ruler"): colour distance is traded against spatial distance * ruler / region.
  // Used by slic, mslic and fast; slico adapts its compactness per cluster and ignores it. > 0.
  float ruler = 10.0f;
  // SLIC iterations. OpenCV's usual is 10; 4 gives nearly the same clusters at ~40% of the time (see
  // superpixels_test throughput). [1, 100]
  int iterations = 4;
  // slic | slico | mslic (cv::ximgproc) | fast (our own SLIC, core/slic_fast.h: SLIC's distance with `ruler`,
  // seeds on a region_size_px grid moved to the lowest gradient in 3x3, run-based connectivity; deterministic).
  // Default fast: ~8x slico's speed (24-47 Mpx/s on 2 threads vs 3-5) at -0.08 / -0.02 F1 on the small block
  // (docs/design.md).
  // pixels: no clustering, every pixel its own node (the paper's per-point Netlets, Section III.B; the ablation
  // of III.C — memory and time grow with the pixel count, for small blocks only).
  std::string algorithm = "fast";
  // The raster is segmented in independent square blocks of this size (bounded memory, parallelism).
  // >= 2 * region_size_px.
  int block_size_px = 1024;
  // > 0 adds depth as an extra SLIC channel so clusters do not straddle depth edges: channel value =
  // depth_weight * (depth_m - median valid depth of the block), i.e. depth_weight is in 8-bit Lab units per
  // metre (10 makes a 1 m step as strong as a colour difference of ~10 a*/b* units). Invalid-depth pixels get
  // the block median. 0 = colour only. >= 0.
  float depth_weight = 0.0f;
  int min_valid_pixels = 4;  // clusters with fewer valid-depth pixels get no representative depth. >= 1
};

struct SuperpixelCluster {
  // Mean pixel CENTRE of the cluster's pixels, image coordinates (pixel (row, col) has centre (col+0.5, row+0.5)).
  float centroid_col = 0, centroid_row = 0;
  // Robust representative depth: median of the cluster's valid depths (mean of the two middle values for an
  // even count); 0 when valid_count < min_valid_pixels.
  float depth_m = 0;
  uint32_t pixel_count = 0;  // all pixels
  uint32_t valid_count = 0;  // pixels with valid depth
};

struct SuperpixelMap {
  int width = 0, height = 0;
  SuperpixelLabels labels;  // cluster index per pixel, 0..clusters.size()-1; width x height
  std::vector<SuperpixelCluster> clusters;
  int32_t label(int row, int col) const { return labels.at(row, col); }
};

// Segments `depth`'s grid. `image` (RGB, 3 channels, or 1-channel grey) may have a different size with the
// same aspect ratio: it is resampled to the depth raster (INTER_AREA when shrinking, bilinear when growing).
// `depth` gives the cluster depths (and the extra channel when depth_weight > 0). Each block of block_size_px
// is segmented independently (clusters never cross block borders); a trailing block narrower than
// 2 * region_size_px is merged into its neighbour. Labels are renumbered in row-major block order and, inside
// a block, in order of first appearance, so the result is deterministic and independent of the thread count
// (each block runs single-threaded; blocks run in parallel with TBB, so memory beyond the output is only that
// of the blocks in flight). Every pixel gets a label, also invalid-depth ones. `packing`: how the labels are held
// (core/superpixel_labels.h). Throws ConfigError for bad options, Error for unusable inputs.
SuperpixelMap ComputeSuperpixels(const RgbImage& image, const DepthMap& depth, const SuperpixelOptions& options,
                                 LabelPacking packing = LabelPacking::kPacked);

// Builds the process's colour-conversion tables that ComputeSuperpixels' first call would otherwise build while
// every other caller waits (OpenCV's RGB -> Lab tables, ~0.1 s of one thread); once per process, thread-safe, and
// a no-op when done. A job runs it beside its first stages (jobs/run_fusion.h), so no superpixel stage waits.
void PrepareSuperpixelTables();

// Throws ConfigError listing every broken rule as "SuperpixelOptions.<field> = v: rule", one per line (an invariant
// of ComputeSuperpixels; the YAML keys superpixels.* are checked by config/option_table.cc).
void ValidateSuperpixelOptions(const SuperpixelOptions& options);

// Fingerprint of everything that changes the segmentation (options and algorithm version); stable across runs
// and platforms (FNV-1a over a fixed little-endian encoding). Cache files store it; it does not cover the
// input rasters themselves.
uint64_t SuperpixelOptionsHash(const SuperpixelOptions& options);

}  // namespace sacfuse
