#pragma once
// How sacfuse turns points into a DSM (docs/dsm-and-ortho.md gives the measurements behind each choice):
// 1. per cell (core/cell_heights.h): the `quantile` of the z of the points in the cell (none below min_points);
//    the median by default: on the aerial-bench blocks it gives the lowest NMAD and RMSE against the LiDAR top
//    surface, for sacfuse's clouds and the peers' alike (a higher quantile or the maximum lifts the noise);
// 2. holes: every 4-connected region of cells without a value whose bounding box is at most max_hole_m on each
//    side, and that does not reach the edge of the cells examined, is filled by inverse-distance weighting
//    (power 2) of the values on its rim (the 8-connected cells around it); larger regions stay nodata.
// Step 2 looks at most DsmHaloCells() cells away, so a block of the raster finished from its cells plus that halo
// (FinishDsm) equals the same cells of the whole raster finished at once: tiles and blocks are seam-free by
// construction.
#include <cstdint>
#include <vector>

#include "core/cell_window.h"

namespace sacfuse {

struct DsmRule {
  double quantile = 0.5;        // of the z of the points in a cell, 0-1 (1 = the highest point)
  int min_points = 1;           // cells with fewer points get no value
  double max_hole_m = 0.0;      // 0 = no hole filling
};

// Cells of context the hole filling reads around a cell.
int64_t DsmHaloCells(const DsmRule& rule, double cell_m);
// The largest hole side filled, in cells (0 = none).
int64_t DsmMaxHoleCells(const DsmRule& rule, double cell_m);

struct DsmFinishStats {
  uint64_t cells_filled = 0;    // in `inner`
};

// Finishes the cells of `inner` from the raw cell values of `outer` (north-up, NaN = none), which must contain
// `inner` grown by DsmHaloCells (cells outside the product's extent are NaN). Returns `inner`'s values, north-up.
std::vector<float> FinishDsm(const std::vector<float>& raw, const CellWindow& outer, const CellWindow& inner,
                             const DsmRule& rule, DsmFinishStats* stats = nullptr);

}  // namespace sacfuse
