#include "eval/dsm_accuracy.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>

#include <fmt/format.h>

#include "core/cell_heights.h"
#include "core/error.h"
#include "core/geo_mask.h"
#include "io/cloud_grid.h"
#include "io/gdal_raster.h"
#include "io/geo_mask_io.h"
#include "io/point_cloud_file.h"

namespace sacfuse {
namespace {

bool IsNoise(uint8_t c) { return c == 7 || c == 18; }

// The class groups a reference cell is scored in ("" = none: unclassified).
std::string ClassGroup(uint8_t c) {
  switch (c) {
    case 2: return "ground";
    case 3: case 4: case 5: return "vegetation";
    case 6: return "building";
    case 9: return "water";
    case 0: case 1: return "";
    default: return "other";
  }
}

// Fills the reference cells without a return: the highest of the 8 neighbours with one, then the nearest filled
// cell (breadth first, 4-connected steps); classes follow their heights.
void FillReference(const CellWindow& w, std::vector<float>* top, std::vector<uint8_t>* cls) {
  const int64_t cols = w.cols, rows = w.rows;
  std::vector<float> t = *top;
  std::vector<uint8_t> c = *cls;
  for (int64_t r = 0; r < rows; ++r) {
    for (int64_t x = 0; x < cols; ++x) {
      const size_t i = static_cast<size_t>(r * cols + x);
      if (!std::isnan((*top)[i])) continue;
      for (int64_t dr = -1; dr <= 1; ++dr) {
        for (int64_t dx = -1; dx <= 1; ++dx) {
          const int64_t rr = r + dr, xx = x + dx;
          if (rr < 0 || xx < 0 || rr >= rows || xx >= cols) continue;
          const size_t j = static_cast<size_t>(rr * cols + xx);
          if (!std::isnan((*top)[j]) && (std::isnan(t[i]) || (*top)[j] > t[i])) t[i] = (*top)[j], c[i] = (*cls)[j];
        }
      }
    }
  }
  std::deque<size_t> queue;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!std::isnan(t[i])) queue.push_back(i);
  }
  while (!queue.empty()) {
    const size_t i = queue.front();
    queue.pop_front();
    const int64_t r = static_cast<int64_t>(i) / cols, x = static_cast<int64_t>(i) % cols;
    const int64_t nr[4] = {r - 1, r + 1, r, r}, nx[4] = {x, x, x - 1, x + 1};
    for (int k = 0; k < 4; ++k) {
      if (nr[k] < 0 || nx[k] < 0 || nr[k] >= rows || nx[k] >= cols) continue;
      const size_t j = static_cast<size_t>(nr[k] * cols + nx[k]);
      if (!std::isnan(t[j])) continue;
      t[j] = t[i];
      c[j] = c[i];
      queue.push_back(j);
    }
  }
  *top = std::move(t);
  *cls = std::move(c);
}

double Median(std::vector<double>* v) {
  const size_t mid = v->size() / 2;
  std::nth_element(v->begin(), v->begin() + static_cast<std::ptrdiff_t>(mid), v->end());
  double m = (*v)[mid];
  if (v->size() % 2 == 0) m = 0.5 * (m + *std::max_element(v->begin(), v->begin() + static_cast<std::ptrdiff_t>(mid)));
  return m;
}

}  // namespace

DsmErrorStats DsmErrorStatsOf(std::vector<double> e, uint64_t cells, double gsd_m) {
  DsmErrorStats s;
  s.cells = cells;
  s.cells_with_value = e.size();
  if (cells == 0) return s;
  s.completeness = static_cast<double>(e.size()) / static_cast<double>(cells);
  if (e.empty()) return s;
  double sq = 0;
  uint64_t within = 0;
  for (const double v : e) {
    sq += v * v;
    within += std::abs(v) <= 2 * gsd_m ? 1 : 0;
  }
  s.rmse_m = std::sqrt(sq / static_cast<double>(e.size()));
  s.within_2gsd = static_cast<double>(within) / static_cast<double>(cells);
  s.median_m = Median(&e);
  for (double& v : e) v = std::abs(v - s.median_m);
  s.nmad_m = 1.4826 * Median(&e);
  return s;
}

DsmAccuracy EvaluateDsm(const DsmAccuracyRequest& req) {
  const RasterFile dsm(req.dsm_path);
  PointCloudFile reference(req.reference_las);
  const CellWindow area = dsm.window().Intersection(CellWindowCovering(reference.bounds_xy(), dsm.window().cell_m));
  DsmAccuracy out;
  out.dsm_path = req.dsm_path;
  out.cell_m = dsm.window().cell_m;
  out.gsd_m = req.gsd_m;
  if (area.empty()) throw InputError(req.dsm_path, "does not overlap the reference " + req.reference_las);

  CloudGridOptions options;
  options.quantile = 1.0;  // the highest return
  options.max_points_in_memory = req.max_points_in_memory;
  options.keep = [](uint8_t c) { return !IsNoise(c); };
  std::vector<float> top = GridCloud(reference, area, options).values;
  // The class of each cell's highest return (the highest class code among returns at that height).
  std::vector<uint8_t> cls(area.size(), 0);
  bool classified = false;
  const CellHeights locate(area);
  CloudChunk chunk;
  reference.Rewind();
  while (reference.Read(&chunk, 1 << 16) > 0) {
    for (size_t i = 0; i < chunk.xyz.size(); ++i) {
      const uint8_t c = chunk.classification[i];
      int64_t col = 0, row = 0;
      if (IsNoise(c) || !locate.CellOf(chunk.xyz[i].x(), chunk.xyz[i].y(), &col, &row)) continue;
      const size_t k = area.Index(col, row);
      if (static_cast<float>(chunk.xyz[i].z()) == top[k]) cls[k] = std::max(cls[k], c);
      classified = classified || !ClassGroup(c).empty();
    }
  }
  FillReference(area, &top, &cls);

  std::optional<GeoMask> mask;
  if (!req.mask_png.empty()) mask = ReadGeoMask(req.mask_png);
  const std::vector<float> values = dsm.ReadFloat(area);
  std::vector<double> e_all;
  uint64_t cells_all = 0;
  std::vector<std::pair<std::string, std::pair<std::vector<double>, uint64_t>>> groups;
  for (int64_t r = 0; r < area.rows; ++r) {
    for (int64_t c = 0; c < area.cols; ++c) {
      const size_t i = static_cast<size_t>(r * area.cols + c);
      if (std::isnan(top[i])) continue;
      const double x = area.west() + (static_cast<double>(c) + 0.5) * area.cell_m;
      const double y = area.north() - (static_cast<double>(r) + 0.5) * area.cell_m;
      if (mask && !mask->Contains(x, y)) continue;
      ++cells_all;
      const bool has = !std::isnan(values[i]);
      const double e = has ? static_cast<double>(values[i]) - static_cast<double>(top[i]) : 0.0;
      if (has) e_all.push_back(e);
      if (!classified) continue;
      std::string group = ClassGroup(cls[i]);
      if (group.empty()) group = "unclassified";
      auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == group; });
      if (it == groups.end()) it = groups.insert(groups.end(), {group, {{}, 0}});
      ++it->second.second;
      if (has) it->second.first.push_back(e);
    }
  }
  out.all = DsmErrorStatsOf(std::move(e_all), cells_all, req.gsd_m);
  std::sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [name, g] : groups) out.by_class.emplace_back(name, DsmErrorStatsOf(std::move(g.first), g.second, req.gsd_m));
  return out;
}

std::string FormatDsmAccuracy(const DsmAccuracy& a) {
  const auto line = [&](const std::string& name, const DsmErrorStats& s) {
    return fmt::format("  {:<14} {:>9} cells  completeness {:6.2f} %  median {:+.3f} m  NMAD {:.3f} m  RMSE {:.3f} m  "
                       "within 2 GSD {:6.2f} %\n",
                       name, s.cells, 100.0 * s.completeness, s.median_m, s.nmad_m, s.rmse_m, 100.0 * s.within_2gsd);
  };
  std::string out = fmt::format("DSM {} (cells of {} m) against the reference's top surface on the same cells:\n",
                                a.dsm_path, a.cell_m);
  out += line("all", a.all);
  for (const auto& [name, s] : a.by_class) out += line(name, s);
  return out;
}

}  // namespace sacfuse
