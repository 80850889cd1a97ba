#include "tools/sim/consistency_graphs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include <Eigen/Core>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/backproject.h"
#include "core/error.h"
#include "io/colmap_array.h"
#include "io/colmap_consistency_graph.h"
#include "tools/sim/sim_workspace.h"

namespace sacfuse::sim {
namespace {

namespace fs = std::filesystem;

int Threads(const ConsistencyGraphOptions& o) { return o.num_threads > 0 ? o.num_threads : tbb::this_task_arena::max_concurrency(); }

// Focal length standing for a camera's pixel footprint (metres per pixel = depth / this).
double Focal(const PinholeCamera& c) { return std::min(c.fx, c.fy); }

// World bounding box of a depth map's valid points, padded by the depth tolerance at its largest depth.
struct PointBox {
  bool valid = false;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());

  bool Intersects(const PointBox& o) const {
    return valid && o.valid && (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
  double OverlapAreaXy(const PointBox& o) const {
    const double w = std::min(hi.x(), o.hi.x()) - std::max(lo.x(), o.lo.x());
    const double h = std::min(hi.y(), o.hi.y()) - std::max(lo.y(), o.lo.y());
    return std::max(0.0, w) * std::max(0.0, h);
  }
};

PointBox BoxOf(const DepthViewRef& v, const ConsistencyGraphOptions& o) {
  const DepthMap& depth = *v.depth;
  const Rigid3d world_from_cam = v.cam_from_world.Inverse();
  std::vector<PointBox> rows(static_cast<size_t>(depth.height));
  std::vector<double> max_depth(rows.size(), 0.0);
  tbb::task_arena(Threads(o)).execute([&] {
  tbb::parallel_for(0, depth.height, [&](int row) {
    PointBox& box = rows[static_cast<size_t>(row)];
    for (int col = 0; col < depth.width; ++col) {
      const float d = depth.at(row, col);
      if (!IsValidDepth(d)) continue;
      const Eigen::Vector3d p = DepthPixelToWorld(v.camera, world_from_cam, col, row, d);
      box.valid = true;
      box.lo = box.lo.cwiseMin(p);
      box.hi = box.hi.cwiseMax(p);
      max_depth[static_cast<size_t>(row)] = std::max(max_depth[static_cast<size_t>(row)], static_cast<double>(d));
    }
  });
  });
  PointBox box;
  double z_max = 0.0;
  for (size_t r = 0; r < rows.size(); ++r) {
    if (!rows[r].valid) continue;
    box.valid = true;
    box.lo = box.lo.cwiseMin(rows[r].lo);
    box.hi = box.hi.cwiseMax(rows[r].hi);
    z_max = std::max(z_max, max_depth[r]);
  }
  const double pad = std::max(o.relative_tolerance * z_max, o.gsd_factor * z_max / Focal(v.camera));
  box.lo.array() -= pad;
  box.hi.array() += pad;
  return box;
}

// Source views of `ref`: intersecting boxes, the max_source_views with the largest horizontal overlap (ties: lower
// index), returned by increasing index.
std::vector<uint32_t> SelectSources(size_t ref, const std::vector<PointBox>& boxes, int max_sources) {
  std::vector<std::pair<double, uint32_t>> candidates;
  for (size_t j = 0; j < boxes.size(); ++j) {
    if (j != ref && boxes[ref].Intersects(boxes[j])) {
      candidates.emplace_back(boxes[ref].OverlapAreaXy(boxes[j]), static_cast<uint32_t>(j));
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  if (static_cast<int>(candidates.size()) > max_sources) candidates.resize(static_cast<size_t>(max_sources));
  std::vector<uint32_t> sources;
  for (const auto& c : candidates) sources.push_back(c.second);
  std::sort(sources.begin(), sources.end());
  return sources;
}

std::string DepthPath(const std::string& dir, const View& v) {
  return (fs::path(dir) / "stereo/depth_maps" / (v.name + ".geometric.bin")).string();
}
std::string GraphPath(const std::string& dir, const View& v) {
  return (fs::path(dir) / "stereo/consistency_graphs" / (v.name + ".geometric.bin")).string();
}

DepthMap ReadDepth(const std::string& path) {
  DepthMap depth = ReadColmapArray(path);
  if (depth.channels != 1) {
    throw InputError(path, std::to_string(depth.channels) + " channels, a depth map has 1");
  }
  return depth;
}

}  // namespace

ConsistencyGraph ComputeConsistencyGraph(size_t ref, const std::vector<DepthViewRef>& views,
                                         const std::vector<uint32_t>& sources, const ConsistencyGraphOptions& o) {
  if (ref >= views.size() || views[ref].depth == nullptr) throw Error("ComputeConsistencyGraph: no reference depth");
  // Per source j, homogeneous pixel coordinates of a reference pixel (u, v) at depth d:
  //   h = K_j (R d K_ref^-1 (u, v, 1) + t) = d (a_row + u_offset * b) + m,  u = h.x / h.z, v = h.y / h.z, z = h.z,
  // with a_row = K_j R K_ref^-1 (0, v, 1), b = K_j R K_ref^-1 (1, 0, 0), m = K_j t (K_j's last row is (0, 0, 1)).
  struct Source {
    uint32_t index;
    const DepthMap* depth;
    Eigen::Matrix3d ray_to_pixel;  // K_j R K_ref^-1
    Eigen::Vector3d m;
    double tolerance_per_m;        // max(relative_tolerance, gsd_factor / focal_j): tolerance / depth
  };
  const DepthViewRef& r = views[ref];
  std::vector<uint32_t> sorted = sources;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  Eigen::Matrix3d k_ref_inv;
  k_ref_inv << 1.0 / r.camera.fx, 0.0, -r.camera.cx / r.camera.fx, 0.0, 1.0 / r.camera.fy,
      -r.camera.cy / r.camera.fy, 0.0, 0.0, 1.0;
  std::vector<Source> src;
  for (const uint32_t j : sorted) {
    if (j == ref) continue;
    if (j >= views.size() || views[j].depth == nullptr) throw Error("ComputeConsistencyGraph: no source depth");
    const PinholeCamera& c = views[j].camera;
    Eigen::Matrix3d k;
    k << c.fx, 0.0, c.cx, 0.0, c.fy, c.cy, 0.0, 0.0, 1.0;
    const Rigid3d j_from_ref = views[j].cam_from_world * r.cam_from_world.Inverse();
    src.push_back({j, views[j].depth, k * j_from_ref.rotation.normalized().toRotationMatrix() * k_ref_inv,
                   k * j_from_ref.translation, std::max(o.relative_tolerance, o.gsd_factor / Focal(c))});
  }
  const DepthMap& depth = *r.depth;
  const int width = depth.width, height = depth.height;
  const double ref_gsd_per_m = o.gsd_factor / Focal(r.camera);
  const uint32_t cap = static_cast<uint32_t>(std::max(0, o.max_views_per_pixel));
  std::vector<uint32_t> counts(static_cast<size_t>(width) * height, 0);
  std::vector<std::vector<uint32_t>> row_lists(static_cast<size_t>(height));
  tbb::task_arena(Threads(o)).execute([&] {
  tbb::parallel_for(0, height, [&](int row) {
    std::vector<uint32_t>& list = row_lists[static_cast<size_t>(row)];
    std::vector<Eigen::Vector3d> a(src.size()), b(src.size());
    for (size_t s = 0; s < src.size(); ++s) {
      a[s] = src[s].ray_to_pixel * Eigen::Vector3d(0.5, row + 0.5, 1.0);
      b[s] = src[s].ray_to_pixel.col(0);
    }
    for (int col = 0; col < width; ++col) {
      const float d = depth.at(row, col);
      if (!IsValidDepth(d)) continue;
      const double ref_tolerance = ref_gsd_per_m * d;
      uint32_t n = 0;
      for (size_t si = 0; si < src.size() && n < cap; ++si) {
        const Source& s = src[si];
        const Eigen::Vector3d h = static_cast<double>(d) * (a[si] + col * b[si]) + s.m;
        const double z = h.z();
        if (!(z > 0.0)) continue;
        const double u = h.x() / z, v = h.y() / z;
        if (!(u >= 0.0 && v >= 0.0 && u < s.depth->width && v < s.depth->height)) continue;
        const float dj = s.depth->at(static_cast<int>(v), static_cast<int>(u));
        if (!IsValidDepth(dj)) continue;
        if (std::abs(static_cast<double>(dj) - z) > std::max(s.tolerance_per_m * z, ref_tolerance)) continue;
        list.push_back(s.index);
        ++n;
      }
      counts[static_cast<size_t>(row) * width + col] = n;
    }
  });
  });
  ConsistencyGraph graph;
  graph.width = width;
  graph.height = height;
  graph.pixel_offsets.resize(counts.size() + 1, 0);
  for (size_t p = 0; p < counts.size(); ++p) graph.pixel_offsets[p + 1] = graph.pixel_offsets[p] + counts[p];
  graph.view_indices.reserve(graph.pixel_offsets.back());
  for (auto& list : row_lists) {
    graph.view_indices.insert(graph.view_indices.end(), list.begin(), list.end());
    std::vector<uint32_t>().swap(list);
  }
  return graph;
}

ConsistencyGraphSummary WriteConsistencyGraphs(const std::string& dir, const std::vector<View>& views,
                                               const ConsistencyGraphOptions& o, const ConsistencyProgress& progress) {
  const size_t n = views.size();
  if (n > static_cast<size_t>(std::numeric_limits<int32_t>::max())) throw Error(dir + ": too many views");
  // Pass 1: each depth map once, for its camera at depth resolution and its point box.
  std::vector<DepthViewRef> refs(n);
  std::vector<PointBox> boxes(n);
  for (size_t i = 0; i < n; ++i) {
    const DepthMap depth = ReadDepth(DepthPath(dir, views[i]));
    refs[i].camera = views[i].camera.Scaled(depth.width, depth.height);
    refs[i].cam_from_world = views[i].cam_from_world;
    refs[i].depth = &depth;
    boxes[i] = BoxOf(refs[i], o);
    refs[i].depth = nullptr;
  }
  // Pass 2: per reference view, keep only its own and its sources' depth maps in memory.
  ConsistencyGraphSummary summary;
  std::map<uint32_t, DepthMap> cache;
  for (size_t i = 0; i < n; ++i) {
    const std::vector<uint32_t> sources = SelectSources(i, boxes, o.max_source_views);
    std::vector<uint32_t> needed = sources;
    needed.push_back(static_cast<uint32_t>(i));
    std::sort(needed.begin(), needed.end());
    for (auto it = cache.begin(); it != cache.end();) {
      if (std::binary_search(needed.begin(), needed.end(), it->first)) {
        ++it;
      } else {
        refs[it->first].depth = nullptr;
        it = cache.erase(it);
      }
    }
    for (const uint32_t j : needed) {
      if (cache.count(j)) continue;
      refs[j].depth = &cache.emplace(j, ReadDepth(DepthPath(dir, views[j]))).first->second;
    }
    const ConsistencyGraph graph = ComputeConsistencyGraph(i, refs, sources, o);
    const std::string path = GraphPath(dir, views[i]);
    CreateParentDirs(path);
    WriteColmapConsistencyGraph(path, graph);
    const DepthMap& depth = *refs[i].depth;
    for (size_t p = 0; p < depth.num_pixels(); ++p) {
      if (!IsValidDepth(depth.data[p])) continue;
      ++summary.valid_pixels;
      if (graph.pixel_offsets[p + 1] > graph.pixel_offsets[p]) ++summary.pixels_with_views;
    }
    summary.entries += graph.view_indices.size();
    ++summary.num_graphs;
    if (progress) progress(i + 1, n);
  }
  return summary;
}

}  // namespace sacfuse::sim
