#pragma once
// DSM accuracy (`sacfuse eval --dsm`, the scoring step of `sacfuse run` when it wrote a DSM, `sacfuse bench`), as
// the EuroSDR dense image matching benchmark reports it: the DSM against a reference DSM gridded from the reference
// cloud on the same cells.
//   Reference: per cell of the DSM's lattice the highest reference return (LAS classes 7 and 18, noise, left
//     out: the top surface an airborne scanner sees), its class that return's; cells without a return take the
//     highest of their 8 neighbours, then the nearest filled cell (as ../shared/aerial-bench/score_dsm.py does
//     on its mask grid).
//   Cells scored: those of the DSM's extent inside the evaluation mask (cell centre; the whole reference extent
//     without a mask) and within the reference's bounds.
//   completeness  share of the scored cells where the DSM has a value
//   e = DSM - reference over the scored cells with a value: median, NMAD = 1.4826 median |e - median e|, RMSE,
//     and the share of scored cells with a value and |e| <= 2 GSD ("within 2 GSD", completeness-aware).
//   Split by the reference cells' class when the reference has classes (ground 2, vegetation 3-5, building 6,
//   water 9, other).
#include <string>
#include <utility>
#include <vector>

namespace sacfuse {

struct DsmErrorStats {
  uint64_t cells = 0;             // scored
  uint64_t cells_with_value = 0;  // of those, where the DSM has a value
  double completeness = 0.0;
  double median_m = 0.0, nmad_m = 0.0, rmse_m = 0.0;
  double within_2gsd = 0.0;
};

struct DsmAccuracy {
  std::string dsm_path;
  double cell_m = 0.0;
  double gsd_m = 0.0;
  DsmErrorStats all;
  std::vector<std::pair<std::string, DsmErrorStats>> by_class;  // empty when the reference has no classes
};

struct DsmAccuracyRequest {
  std::string dsm_path;       // a GeoTIFF or VRT on the lattice (io/gdal_raster.h)
  std::string reference_las;
  std::string mask_png;       // "" = none
  double gsd_m = 0.10;
  uint64_t max_points_in_memory = uint64_t{32} << 20;  // gridding the reference (io/cloud_grid.h)
};

// Throws InputError naming a file that cannot be read.
DsmAccuracy EvaluateDsm(const DsmAccuracyRequest& request);

// The statistics of errors `e` over `cells` scored cells (e holds the cells with a value).
DsmErrorStats DsmErrorStatsOf(std::vector<double> e, uint64_t cells, double gsd_m);

// A few lines: completeness, median, NMAD, RMSE, within 2 GSD; one line per class.
std::string FormatDsmAccuracy(const DsmAccuracy& accuracy);

}  // namespace sacfuse
