#pragma once
// One value per cell from the points of a cloud file (core/cell_heights.h's rule), with bounded memory: the
// points are gridded in bands of rows holding at most max_points_in_memory points each (one pass over the file
// to count the points per row, then one pass per band), so any cloud grids in ~8 bytes x that many points.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/cell_window.h"
#include "io/point_cloud_file.h"

namespace sacfuse {

struct CloudGridOptions {
  double quantile = 1.0;       // per cell: the q-quantile of the points' z (1 = highest)
  int min_points = 1;          // cells with fewer points get no value
  uint64_t max_points_in_memory = uint64_t{32} << 20;
  // Optional: only points for which this returns true are gridded (e.g. LiDAR noise classes left out).
  std::function<bool(uint8_t classification)> keep;
};

struct CloudGrid {
  std::vector<float> values;  // north-up over the window, NaN = no value
  uint64_t points_gridded = 0;
  uint64_t points_outside = 0;  // outside the window, or not kept
  int passes = 0;               // reads of the file (count + bands)
};

// Grids `cloud` (rewound first) into `window`. Throws InputError from the reader.
CloudGrid GridCloud(PointCloudFile& cloud, const CellWindow& window, const CloudGridOptions& options);

}  // namespace sacfuse
