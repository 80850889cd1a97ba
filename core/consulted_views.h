#pragma once
// The views a depth pixel consults: the depth maps its combine averages (core/depth_combine.h), the judges of its
// free space (core/point_verdicts.h), the candidates of the better-view search (core/redundancy.h) and the pairs of
// the noise estimate (core/view_noise.h), up to fusion.combine_max_views (40) of them.
//
// Chosen per region of the world, not per view: square cells of `region_m` metres aligned to multiples of it, and
// for each view and cell the views that see most of that view's nodes in the cell, by
//   score = (fraction of the cell's valid nodes of v inside u's whole image) x cos(angle between v's and u's
//           viewing directions),
// those within max_view_angle_deg and seeing at least min_overlap of the nodes, best first, ties by index.
// Why (2026-11-28; docs/design.md): chosen once per view over a whole tile (by
// footprint-box overlap, as the Netlet neighbours are), the list depended on the tile: on the full Dortmund block
// a 256 m tile consulted views that cover part of it well and dropped 241.2 M pixels as redundant against 247.1 M
// for its four 128 m tiles, emitted 17 % more points and scored F1 0.001-0.003 lower. Per cell, the list of a
// place is the same in any tile that holds the cell whole (whole images, not tile windows, count as seen), so the
// cloud no longer depends on the tile size, i.e. on the memory budget.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/sac_nodes.h"
#include "core/sac_view.h"

namespace sacfuse {

struct ConsultOptions {
  int max_views = 40;               // per view and region
  double max_view_angle_deg = 65.0; // degrees
  double min_overlap = 0.05;        // fraction of the region's nodes of the view that the other view must see, 0-1
  double region_m = 128.0;          // side of the regions, metres; 0 = one region per view (all its nodes)
};

class ConsultedViews {
 public:
  ConsultedViews() = default;
  // One list per view, wherever the pixel lies (per_view[v] for view v).
  explicit ConsultedViews(std::vector<std::vector<uint32_t>> per_view);
  // The rule above on the valid nodes of `nodes`. Deterministic for any thread count.
  static ConsultedViews Select(const std::vector<SacView>& views, const NodeTable& nodes,
                               const ConsultOptions& options);

  // The list of view v at a pixel whose own point is `point_in_world` (a point beyond v's cells takes the nearest
  // cell's; a cell without nodes of v takes v's list over all its nodes).
  const std::vector<uint32_t>& At(uint32_t v, const Eigen::Vector3d& point_in_world) const {
    const Grid& g = grids_[v];
    if (g.cols == 0) return lists_[g.whole_view];
    const auto cell = [&](double x, int64_t first, int count) {
      const int64_t i = static_cast<int64_t>(std::floor(x / region_m_)) - first;
      return static_cast<int>(std::clamp<int64_t>(i, 0, count - 1));
    };
    const int c = cell(point_in_world.x(), g.first_col, g.cols), r = cell(point_in_world.y(), g.first_row, g.rows);
    return lists_[g.list_of_cell[static_cast<size_t>(r) * g.cols + c]];
  }
  size_t num_views() const { return grids_.size(); }
  // The longest list (at most ConsultOptions::max_views).
  size_t max_list_size() const;
  // The same choice with every list stably sorted by `less`.
  template <typename Less>
  ConsultedViews Sorted(Less less) const {
    ConsultedViews out = *this;
    for (auto& list : out.lists_) std::stable_sort(list.begin(), list.end(), less);
    return out;
  }

 private:
  struct Grid {
    int64_t first_col = 0, first_row = 0;  // cell indices floor(x / region_m), floor(y / region_m) of the first
    int cols = 0, rows = 0;                // 0: one list for the whole view
    std::vector<uint32_t> list_of_cell;    // row-major, index into lists_
    uint32_t whole_view = 0;               // index into lists_ of the list over all the view's nodes
  };
  double region_m_ = 0.0;
  std::vector<std::vector<uint32_t>> lists_;
  std::vector<Grid> grids_;  // per view
};

}  // namespace sacfuse
