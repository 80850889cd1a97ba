#include "io/dsm_file.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/cell_heights.h"
#include "core/error.h"

namespace sacfuse {
namespace {

DsmWriteStats Assemble(const CellWindow& extent, const RawCellReader& read, const DsmRule& rule,
                       const RasterFormat& format, const RasterOutput& output) {
  const auto start = std::chrono::steady_clock::now();
  DsmWriteStats stats;
  const CellFinisher finish = [&](const std::vector<float>& raw, const CellWindow& outer, const CellWindow& inner) {
    // Raw cells with a value, counted once (in their own block), by rows on the job's threads.
    const CellWindow inside = inner.Intersection(extent);
    stats.raw_cells_with_value += tbb::parallel_reduce(
        tbb::blocked_range<int64_t>(inside.row0, inside.row0 + inside.rows), uint64_t{0},
        [&](const tbb::blocked_range<int64_t>& rows, uint64_t n) {
          for (int64_t row = rows.begin(); row < rows.end(); ++row) {
            const float* v = raw.data() + outer.Index(inside.col0, row);
            for (int64_t c = 0; c < inside.cols; ++c) n += std::isnan(v[c]) ? 0 : 1;
          }
          return n;
        },
        std::plus<>());
    return FinishDsm(raw, outer, inner, rule, &stats.finish);
  };
  stats.assembly = AssembleRaster(extent, DsmHaloCells(rule, extent.cell_m), read, finish, format, output);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace

RasterFormat DsmRasterFormat(const std::string& crs_wkt) {
  RasterFormat f;
  f.nodata = kDsmNodata;
  f.crs_wkt = crs_wkt;
  f.overview_resampling = "AVERAGE";
  f.band_descriptions = {"height (m)"};
  return f;
}

RasterFormat DsmRawFormat(const std::string& crs_wkt) {
  RasterFormat f;
  f.nodata = std::numeric_limits<double>::quiet_NaN();
  f.crs_wkt = crs_wkt;
  return f;
}

DsmWriteStats WriteDsm(const std::vector<float>& raw, const CellWindow& extent, const DsmRule& rule,
                       const RasterFormat& format, const RasterOutput& output) {
  const RawCellReader read = [&](const CellWindow& w) {
    std::vector<float> out(w.size(), kNoCellValue);
    const CellWindow common = w.Intersection(extent);
    if (common.empty()) return out;
    tbb::parallel_for(common.row0, common.row0 + common.rows, [&](int64_t row) {  // rows on the job's threads
      std::copy_n(raw.begin() + static_cast<std::ptrdiff_t>(extent.Index(common.col0, row)), common.cols,
                  out.begin() + static_cast<std::ptrdiff_t>(w.Index(common.col0, row)));
    });
    return out;
  };
  return Assemble(extent, read, rule, format, output);
}

CloudGridOptions DsmCloudGridOptions(const DsmRule& rule, uint64_t max_points_in_memory) {
  CloudGridOptions options;
  options.quantile = rule.quantile;
  options.min_points = rule.min_points;
  options.max_points_in_memory = max_points_in_memory;
  return options;
}

DsmWriteStats WriteDsmOfCloud(PointCloudFile& cloud, const CellWindow& extent, const DsmRule& rule,
                              const RasterFormat& format, const RasterOutput& output, uint64_t max_points_in_memory,
                              CloudGrid* grid) {
  CloudGrid raw = GridCloud(cloud, extent, DsmCloudGridOptions(rule, max_points_in_memory));
  DsmWriteStats stats;
  if (raw.points_gridded > 0) stats = WriteDsm(raw.values, extent, rule, format, output);
  if (grid != nullptr) {
    raw.values.clear();
    *grid = std::move(raw);
  }
  return stats;
}

DsmWriteStats WriteDsmFromRawFiles(const std::vector<std::string>& raw_files, const RawCellPatch& patch,
                                   const CellWindow& extent, const DsmRule& rule, const RasterFormat& format,
                                   const RasterOutput& output) {
  if (raw_files.empty() && patch.empty()) throw Error("WriteDsmFromRawFiles: no raw cells");
  // The files are read on the job's threads, each opened by the task that reads it (opening one parses its CRS):
  // first their windows, then per block the files that meet it, placed in file order (later files win where they
  // overlap, as in a mosaic of them; a tiled run's cores do not overlap).
  std::vector<CellWindow> windows(raw_files.size());
  tbb::parallel_for(size_t{0}, raw_files.size(), [&](size_t k) {
    windows[k] = RasterFile(raw_files[k]).window();
    windows[k].cell_m = extent.cell_m;
  });
  const RawCellReader read = [&](const CellWindow& w) {
    std::vector<float> v(w.size(), kNoCellValue);
    std::vector<size_t> meeting;
    for (size_t k = 0; k < raw_files.size(); ++k) {
      if (!w.Intersection(windows[k]).empty()) meeting.push_back(k);
    }
    std::vector<std::vector<float>> parts(meeting.size());
    tbb::parallel_for(size_t{0}, meeting.size(), [&](size_t m) {
      parts[m] = RasterFile(raw_files[meeting[m]]).ReadFloat(w.Intersection(windows[meeting[m]]));
    });
    for (size_t m = 0; m < meeting.size(); ++m) {
      const CellWindow common = w.Intersection(windows[meeting[m]]);
      const int64_t x0 = common.XOffsetIn(w), y0 = common.YOffsetIn(w);
      for (int64_t r = 0; r < common.rows; ++r) {
        for (int64_t c = 0; c < common.cols; ++c) {
          const float value = parts[m][static_cast<size_t>(r * common.cols + c)];
          if (!std::isnan(value)) v[static_cast<size_t>((y0 + r) * w.cols + x0 + c)] = value;
        }
      }
    }
    for (int64_t col = w.col0; col < w.col0 + w.cols; ++col) {
      for (auto it = patch.lower_bound({col, w.row0}); it != patch.end() && it->first.first == col &&
                                                       it->first.second < w.row0 + w.rows;
           ++it) {
        v[w.Index(col, it->first.second)] = it->second;
      }
    }
    // Cells outside the product's extent have no value (the tiles' windows never leave it; kept explicit).
    for (int64_t r = 0; r < w.rows; ++r) {
      for (int64_t c = 0; c < w.cols; ++c) {
        if (!extent.Contains(w.col0 + c, w.row0 + w.rows - 1 - r)) v[static_cast<size_t>(r * w.cols + c)] = kNoCellValue;
      }
    }
    return v;
  };
  return Assemble(extent, read, rule, format, output);
}

}  // namespace sacfuse
