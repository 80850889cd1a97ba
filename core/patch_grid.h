#pragma once
// A raster cut into patches, for visiting its pixels in a cache-friendly order (issue 13). A pixel's tests and its
// combine read the other views' depth maps around its point, and the next pixel of a patch reads next to it, so those
// reads stay in cache. Row by row, a wide view (8,176 px at Dortmund scale) crosses an oblique view's rows at an
// angle and touches a new cache line of each of 40 views per pixel, evicted before the next row comes back to it:
// visiting a Dortmund tile in patches made it 1.2x faster with the same output.
#include <algorithm>

#include "core/pixel_window.h"

namespace sacfuse {

// Patches of patch_rows x patch_cols pixels (clipped at the raster's edges), numbered band by band (a band is one
// row of patches) and left to right within a band.
class PatchGrid {
 public:
  PatchGrid(int height, int width, int patch_rows, int patch_cols)
      : height_(height), width_(width), patch_rows_(patch_rows), patch_cols_(patch_cols),
        bands_((height + patch_rows - 1) / patch_rows), per_band_((width + patch_cols - 1) / patch_cols) {}

  int bands() const { return bands_; }
  int patches_per_band() const { return per_band_; }
  int size() const { return bands_ * per_band_; }
  // Patch `index` (0 <= index < size()).
  PixelWindow Patch(int index) const {
    const int band = index / per_band_, column = index % per_band_;
    PixelWindow w;
    w.row_begin = band * patch_rows_;
    w.row_end = std::min(height_, w.row_begin + patch_rows_);
    w.col_begin = column * patch_cols_;
    w.col_end = std::min(width_, w.col_begin + patch_cols_);
    return w;
  }
  // Rows [begin, end) of band `band`.
  int BandRowBegin(int band) const { return band * patch_rows_; }
  int BandRowEnd(int band) const { return std::min(height_, (band + 1) * patch_rows_); }

 private:
  int height_, width_, patch_rows_, patch_cols_, bands_, per_band_;
};

}  // namespace sacfuse
