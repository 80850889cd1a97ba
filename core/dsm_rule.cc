#include "core/dsm_rule.h"

#include <algorithm>
#include <cmath>

#include "core/cell_heights.h"
#include "core/error.h"

namespace sacfuse {
namespace {

// Fills the small holes of `v` among the cells [c0, c1) x [r0, r1) of `outer` (raster offsets).
void FillHoles(std::vector<float>* v, int64_t c0, int64_t c1, int64_t r0, int64_t r1, int64_t max_cells,
               const CellWindow& outer, const CellWindow& inner, uint64_t* filled_in) {
  if (max_cells <= 0) return;
  // Holes and rims are read from the values as they were: a hole's fill never depends on whether a neighbouring
  // hole (diagonally adjacent, so in its rim) was filled first, so every window gets the same bits.
  const std::vector<float> a = *v;
  const int64_t w = outer.cols;
  const auto index = [w](int64_t x, int64_t y) { return static_cast<size_t>(y * w + x); };
  std::vector<int32_t> label(a.size(), 0);  // hole component of each cell, 0 = none yet
  std::vector<std::pair<int64_t, int64_t>> component, stack, rim;
  std::vector<float> fill;
  const int64_t ix0 = inner.XOffsetIn(outer), iy0 = inner.YOffsetIn(outer);
  int32_t next = 0;
  for (int64_t y0 = r0; y0 < r1; ++y0) {
    for (int64_t x0 = c0; x0 < c1; ++x0) {
      if (!std::isnan(a[index(x0, y0)]) || label[index(x0, y0)] != 0) continue;
      const int32_t id = ++next;
      component.clear();
      stack.assign(1, {x0, y0});
      label[index(x0, y0)] = id;
      int64_t xmin = x0, xmax = x0, ymin = y0, ymax = y0;
      bool open = false;  // reaches the edge of the cells examined
      while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
        if (x == c0 || x == c1 - 1 || y == r0 || y == r1 - 1) open = true;
        // A hole that stays unfilled (open, or too large) is only labelled: its cells are not kept (the empty land
        // around a cloud is one such hole of most of the block's cells).
        if (!open && xmax - xmin < max_cells && ymax - ymin < max_cells) component.push_back({x, y});
        const int64_t nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
        for (int k = 0; k < 4; ++k) {
          if (nx[k] < c0 || nx[k] >= c1 || ny[k] < r0 || ny[k] >= r1) continue;
          const size_t n = index(nx[k], ny[k]);
          if (label[n] != 0 || !std::isnan(a[n])) continue;
          label[n] = id;
          stack.push_back({nx[k], ny[k]});
        }
      }
      if (open || xmax - xmin + 1 > max_cells || ymax - ymin + 1 > max_cells) continue;
      // The rim (valid cells 8-adjacent to the hole) in raster order, so that every window sums it in the same
      // order and gets the same bits.
      rim.clear();
      for (int64_t y = ymin - 1; y <= ymax + 1; ++y) {
        for (int64_t x = xmin - 1; x <= xmax + 1; ++x) {
          if (std::isnan(a[index(x, y)])) continue;
          bool touches = false;
          for (int64_t dy = -1; dy <= 1 && !touches; ++dy) {
            for (int64_t dx = -1; dx <= 1 && !touches; ++dx) {
              const int64_t hx = x + dx, hy = y + dy;
              touches = hx >= c0 && hx < c1 && hy >= r0 && hy < r1 && label[index(hx, hy)] == id;
            }
          }
          if (touches) rim.push_back({x, y});
        }
      }
      if (rim.empty()) continue;
      fill.assign(component.size(), 0.0f);
      for (size_t i = 0; i < component.size(); ++i) {
        const auto [x, y] = component[i];
        double sum = 0, weights = 0;
        for (const auto& [rx, ry] : rim) {
          const double wgt = 1.0 / static_cast<double>((rx - x) * (rx - x) + (ry - y) * (ry - y));
          sum += wgt * static_cast<double>(a[index(rx, ry)]);
          weights += wgt;
        }
        fill[i] = static_cast<float>(sum / weights);
      }
      for (size_t i = 0; i < component.size(); ++i) {
        const auto [x, y] = component[i];
        (*v)[index(x, y)] = fill[i];
        if (x >= ix0 && x < ix0 + inner.cols && y >= iy0 && y < iy0 + inner.rows) ++*filled_in;
      }
    }
  }
}

}  // namespace

int64_t DsmMaxHoleCells(const DsmRule& rule, double cell_m) {
  return rule.max_hole_m > 0 ? static_cast<int64_t>(std::floor(rule.max_hole_m / cell_m + 1e-9)) : 0;
}

int64_t DsmHaloCells(const DsmRule& rule, double cell_m) { return DsmMaxHoleCells(rule, cell_m) + 2; }

std::vector<float> FinishDsm(const std::vector<float>& raw, const CellWindow& outer, const CellWindow& inner,
                             const DsmRule& rule, DsmFinishStats* stats) {
  const int64_t halo = DsmHaloCells(rule, inner.cell_m);
  if (raw.size() != outer.size() || outer.Intersection(inner.Grown(halo)) != inner.Grown(halo)) {
    throw Error("FinishDsm: the raw window must hold the cells to finish plus a halo of " + std::to_string(halo) +
                " cells");
  }
  DsmFinishStats local;
  std::vector<float> v = raw;
  FillHoles(&v, 0, outer.cols, 0, outer.rows, DsmMaxHoleCells(rule, inner.cell_m), outer, inner, &local.cells_filled);
  std::vector<float> out(inner.size());
  const int64_t x0 = inner.XOffsetIn(outer), y0 = inner.YOffsetIn(outer);
  for (int64_t y = 0; y < inner.rows; ++y) {
    std::copy_n(v.begin() + static_cast<std::ptrdiff_t>((y0 + y) * outer.cols + x0), inner.cols,
                out.begin() + static_cast<std::ptrdiff_t>(y * inner.cols));
  }
  if (stats != nullptr) stats->cells_filled += local.cells_filled;
  return out;
}

}  // namespace sacfuse
