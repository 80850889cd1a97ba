#include "io/cloud_grid.h"

#include <algorithm>
#include <atomic>
#include <utility>

#include "core/cell_heights.h"

namespace sacfuse {
namespace {

// Bands of whole rows (north first) holding at most `max_points` points each (a row holding more is a band of
// its own).
std::vector<CellWindow> RowBands(const CellWindow& window, const std::vector<uint64_t>& per_row, uint64_t max_points) {
  std::vector<CellWindow> bands;
  int64_t top = window.rows;  // rows [begin, top) counted from row0
  while (top > 0) {
    int64_t begin = top - 1;
    uint64_t n = per_row[static_cast<size_t>(begin)];
    while (begin > 0 && n + per_row[static_cast<size_t>(begin - 1)] <= max_points) {
      n += per_row[static_cast<size_t>(--begin)];
    }
    CellWindow band = window;
    band.row0 = window.row0 + begin;
    band.rows = top - begin;
    bands.push_back(band);
    top = begin;
  }
  return bands;
}

}  // namespace

CloudGrid GridCloud(PointCloudFile& cloud, const CellWindow& window, const CloudGridOptions& options) {
  CloudGrid out;
  if (window.empty()) return out;
  const CellHeights locate(window);  // the cell of each point, one rule for every band
  const auto kept = [&](uint8_t c) { return !options.keep || options.keep(c); };
  CloudChunk chunk;
  std::vector<CellWindow> bands;
  std::vector<uint64_t> band_points;  // the points each band will hold (at most)
  if (cloud.point_count() <= options.max_points_in_memory) {
    bands.push_back(window);
    band_points.push_back(cloud.point_count());
  } else {
    std::vector<uint64_t> per_row(static_cast<size_t>(window.rows), 0);
    cloud.Rewind();
    ++out.passes;
    while (cloud.Read(&chunk, kCloudReadChunkPoints) > 0) {
      for (size_t i = 0; i < chunk.xyz.size(); ++i) {
        int64_t col = 0, row = 0;
        if (kept(chunk.classification[i]) && locate.CellOf(chunk.xyz[i].x(), chunk.xyz[i].y(), &col, &row)) {
          ++per_row[static_cast<size_t>(row - window.row0)];
        }
      }
    }
    bands = RowBands(window, per_row, options.max_points_in_memory);
    out.values.assign(window.size(), kNoCellValue);  // filled band by band
    for (const CellWindow& band : bands) {
      uint64_t n = 0;
      for (int64_t r = band.row0; r < band.row0 + band.rows; ++r) n += per_row[static_cast<size_t>(r - window.row0)];
      band_points.push_back(n);
    }
  }
  for (size_t b = 0; b < bands.size(); ++b) {
    const CellWindow& band = bands[b];
    CellHeights heights(band);
    heights.Reserve(band_points[b] + kCloudReadChunkPoints);  // a read's points are added before those outside go
    cloud.Rewind();
    ++out.passes;
    const bool count_outside = bands.size() == 1 || &band == &bands.front();
    while (cloud.Read(&chunk, kCloudReadChunkPoints) > 0) {
      std::atomic<uint64_t> outside{0};
      heights.AddInParallel(chunk.xyz.size(), [&](size_t i, int64_t* col, int64_t* row, double* z) {
        const Eigen::Vector3d& p = chunk.xyz[i];
        if (!kept(chunk.classification[i]) || !locate.CellOf(p.x(), p.y(), col, row)) {
          if (count_outside) outside.fetch_add(1, std::memory_order_relaxed);
          return false;
        }
        *z = p.z();
        return band.Contains(*col, *row);
      });
      out.points_outside += outside.load();
    }
    out.points_gridded += heights.points();
    std::vector<float> v = heights.Reduce(options.quantile, options.min_points);
    if (bands.size() == 1) {
      out.values = std::move(v);  // the whole window: no copy on one thread
    } else {
      std::copy(v.begin(), v.end(),
                out.values.begin() + static_cast<std::ptrdiff_t>(band.YOffsetIn(window) * window.cols));
    }
  }
  cloud.Rewind();
  return out;
}

}  // namespace sacfuse
