#include "core/consulted_views.h"

#include <map>
#include <utility>

#include <tbb/parallel_for.h>

#include "core/view_neighbors.h"

namespace sacfuse {
namespace {

// Whether a world point lies in front of view u and inside its whole image (the same in every tile).
bool SeenBy(const SacView& u, const Eigen::Vector3d& point_in_world) {
  const Eigen::Vector3d in_u = u.PointInCamera(point_in_world);
  if (in_u.z() <= 0) return false;
  const Eigen::Vector2d uv = u.view.camera.Project(in_u);
  return uv.x() >= 0 && uv.y() >= 0 && uv.x() < u.view.camera.width && uv.y() < u.view.camera.height;
}

// The best views of v for a region where `seen[u]` of its `num_nodes` nodes lie inside view u's image (see the
// header).
std::vector<uint32_t> BestViews(uint32_t v, const std::vector<uint32_t>& seen, size_t num_nodes,
                                const std::vector<double>& cos_angle, double cos_max, const ConsultOptions& options) {
  std::vector<std::pair<double, uint32_t>> scored;
  for (uint32_t u = 0; u < seen.size() && num_nodes > 0; ++u) {
    if (u == v || cos_angle[u] < cos_max || seen[u] == 0) continue;
    const double fraction = static_cast<double>(seen[u]) / static_cast<double>(num_nodes);
    if (fraction < options.min_overlap) continue;
    scored.emplace_back(fraction * cos_angle[u], u);
  }
  return BestScoredViews(std::move(scored), options.max_views);
}

}  // namespace

ConsultedViews::ConsultedViews(std::vector<std::vector<uint32_t>> per_view) : lists_(std::move(per_view)) {
  grids_.resize(lists_.size());
  for (uint32_t v = 0; v < lists_.size(); ++v) grids_[v].whole_view = v;
}

size_t ConsultedViews::max_list_size() const {
  size_t most = 0;
  for (const auto& list : lists_) most = std::max(most, list.size());
  return most;
}

ConsultedViews ConsultedViews::Select(const std::vector<SacView>& views, const NodeTable& nodes,
                                      const ConsultOptions& options) {
  const size_t n = views.size();
  const double cos_max = std::cos(options.max_view_angle_deg * M_PI / 180.0);
  std::vector<Eigen::Vector3d> directions(n);
  for (size_t v = 0; v < n; ++v) directions[v] = views[v].view.ViewDirectionInWorld();
  std::vector<std::vector<Eigen::Vector3d>> points(n);
  for (const SacNode& node : nodes.nodes) {
    if (node.valid) points[node.view].push_back(node.point_in_world);
  }
  // Per view: its list over all nodes first (local index 0), then one per region holding nodes.
  std::vector<std::vector<std::vector<uint32_t>>> view_lists(n);
  std::vector<Grid> grids(n);
  tbb::parallel_for(size_t{0}, n, [&](size_t vi) {
    const uint32_t v = static_cast<uint32_t>(vi);
    std::vector<double> cos_angle(n);
    for (size_t u = 0; u < n; ++u) cos_angle[u] = directions[v].dot(directions[u]);
    // Each node's region (row, col) and, per region, how many of its nodes each view sees.
    const bool regional = options.region_m > 0;
    std::map<std::pair<int64_t, int64_t>, uint32_t> region_index;
    std::vector<uint32_t> region_of(points[v].size(), 0);
    for (size_t i = 0; i < points[v].size() && regional; ++i) {
      const std::pair<int64_t, int64_t> cell{static_cast<int64_t>(std::floor(points[v][i].y() / options.region_m)),
                                             static_cast<int64_t>(std::floor(points[v][i].x() / options.region_m))};
      region_of[i] = region_index.emplace(cell, static_cast<uint32_t>(region_index.size())).first->second;
    }
    const size_t regions = region_index.size();
    std::vector<std::vector<uint32_t>> seen(regions + 1, std::vector<uint32_t>(n, 0));  // [regions]: the whole view
    std::vector<size_t> num_nodes(regions + 1, 0);
    for (size_t i = 0; i < points[v].size(); ++i) {
      ++num_nodes[region_of[i]];
      for (uint32_t u = 0; u < n; ++u) {
        if (u != v && cos_angle[u] >= cos_max) seen[region_of[i]][u] += SeenBy(views[u], points[v][i]);
      }
    }
    if (regional) {
      for (size_t r = 0; r < regions; ++r) {
        for (uint32_t u = 0; u < n; ++u) seen[regions][u] += seen[r][u];
      }
      num_nodes[regions] = points[v].size();
    }
    auto& lists = view_lists[v];
    const size_t whole = regional ? regions : 0;
    lists.push_back(BestViews(v, seen[whole], num_nodes[whole], cos_angle, cos_max, options));
    if (!regional || region_index.empty()) return;
    Grid& g = grids[v];
    int64_t last_row = region_index.begin()->first.first, last_col = region_index.begin()->first.second;
    g.first_row = last_row;
    g.first_col = last_col;
    for (const auto& [cell, unused] : region_index) {
      g.first_row = std::min(g.first_row, cell.first);
      g.first_col = std::min(g.first_col, cell.second);
      last_row = std::max(last_row, cell.first);
      last_col = std::max(last_col, cell.second);
    }
    g.rows = static_cast<int>(last_row - g.first_row + 1);
    g.cols = static_cast<int>(last_col - g.first_col + 1);
    g.list_of_cell.assign(static_cast<size_t>(g.rows) * g.cols, 0);  // regions without nodes: the whole view's list
    for (const auto& [cell, r] : region_index) {
      g.list_of_cell[static_cast<size_t>(cell.first - g.first_row) * g.cols + (cell.second - g.first_col)] =
          static_cast<uint32_t>(lists.size());
      lists.push_back(BestViews(v, seen[r], num_nodes[r], cos_angle, cos_max, options));
    }
  });
  ConsultedViews out;
  out.region_m_ = options.region_m;
  for (size_t v = 0; v < n; ++v) {
    const uint32_t base = static_cast<uint32_t>(out.lists_.size());
    grids[v].whole_view = base;
    for (uint32_t& index : grids[v].list_of_cell) index += base;
    for (auto& list : view_lists[v]) out.lists_.push_back(std::move(list));
  }
  out.grids_ = std::move(grids);
  return out;
}

}  // namespace sacfuse
