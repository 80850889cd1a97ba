#pragma once
// A view's superpixels on disk, so later runs and tiles reuse them instead of re-running SLIC.
//
// Binary layout, all little-endian:
//   char[8] magic, u32 width, u32 height, u64 num_clusters, u64 options_hash   (32-byte header)
//   magic "SACSPX02" (written whenever it fits, issue 13: half the disk of the int32 layout):
//     u32 band_base[ceil(height / 64)]   the smallest label of each band of 64 rows
//     u16 offset[height][width]          label = band_base[row / 64] + offset
//   magic "SACSPX01" (written when some band spans more than 65,535 labels; still read):
//     int32 labels[height][width]
//   per cluster: f32 centroid_col, f32 centroid_row, f32 depth_m, u32 pixel_count, u32 valid_count  (20 bytes)
// Labels are row-major, so a row window is one contiguous seek + read per row. Our SLIC segments 1024 px blocks
// one after another and numbers their clusters block by block, so a band (64 rows: never across two block rows)
// spans at most the clusters of one block row: measured 7,600-11,700 on the Dortmund preset at scale 0.5 (3,066-
// 4,088 px wide); at full scale (8,176 px, 16 px regions) at most ~33,000.
// The file length must match exactly. options_hash is SuperpixelOptionsHash() of the options that produced
// the map: compare it before reusing a file.
#include <cstdint>
#include <string>
#include <vector>

#include "core/pixel_window.h"
#include "core/superpixels.h"

namespace sacfuse {

// Atomic (temp file, fsync, rename); creates missing parent folders. Throws Error when `map` is inconsistent
// (labels size or range) or the file cannot be written.
void WriteSuperpixels(const std::string& path, const SuperpixelMap& map, uint64_t options_hash);

struct SuperpixelFileInfo {
  int width = 0, height = 0;
  uint64_t num_clusters = 0, options_hash = 0;
};
// Header only (also checks the file length). Throws InputError naming the file.
SuperpixelFileInfo ReadSuperpixelInfo(const std::string& path);

// The whole map. Validates magic, sizes vs file length, every label in range, cluster pixel counts against the
// labels and finite cluster values; throws InputError naming the file.
SuperpixelMap ReadSuperpixels(const std::string& path);

// Rows [row_begin, row_end) of the label raster (width x (row_end - row_begin); row r of the result is image
// row row_begin + r) plus the whole cluster table (centroids stay in full-image coordinates). Labels read are
// range-checked. Throws InputError for a bad file, Error for a bad row range.
SuperpixelMap ReadSuperpixelRows(const std::string& path, int row_begin, int row_end);

// The labels of `window` (row-major, window.width() per row; each row one seek + read), range-checked against the
// file's cluster count, which *info receives. Throws InputError for a bad file, Error for a window outside it.
std::vector<int32_t> ReadSuperpixelLabelWindow(const std::string& path, const PixelWindow& window,
                                               SuperpixelFileInfo* info = nullptr);

// The whole cluster table (validated as in ReadSuperpixels except the sum of pixel counts, which needs the labels
// only in part: it is checked against the raster size). Throws InputError naming the file.
std::vector<SuperpixelCluster> ReadSuperpixelClusters(const std::string& path);

}  // namespace sacfuse
