#include "core/correspondences.h"

#include <algorithm>
#include <cmath>

#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

constexpr uint32_t kNone = CorrespondenceFinder::kNoCorrespondent;

// Node of view `b` whose superpixel holds the projection of `point`; kNone when outside, invalid, or (with
// `depth_test`) when view b's depth there disagrees with the point's depth (occluded, or the point floats).
// `sigma_a_m`: the node's depth noise in its own view, metres (with noise factors; else unused).
uint32_t NodeAtProjection(const SacView& view_b, uint32_t b, const Eigen::Vector3d& point, const NodeTable& nodes,
                          const SacOptions& options, bool depth_test, const std::vector<double>& noise_factor = {},
                          double sigma_a_m = 0.0) {
  const DepthLookup lookup = LookupDepth(view_b, point);
  if (!lookup.inside) return kNone;
  if (depth_test && !DepthAgrees(view_b, lookup, options)) {
    if (noise_factor.empty() || options.correspondence_tolerance_sigmas <= 0 || !IsValidDepth(lookup.stored_depth_m)) {
      return kNone;
    }
    const double sigma_b = noise_factor[b] * DepthNoiseScale(view_b, lookup.z_m);
    if (!AgreeWithinSigmas(lookup.stored_depth_m - lookup.z_m, sigma_a_m, sigma_b,
                           options.correspondence_tolerance_sigmas)) {
      return kNone;
    }
  }
  const uint32_t id = nodes.Id(b, static_cast<uint32_t>(view_b.superpixels->label(lookup.row, lookup.col)));
  return nodes.nodes[id].valid ? id : kNone;
}

// The nodes as points for the proximity strategy: valid nodes relative to a local origin (a k-d tree in metres near
// zero keeps precision).
struct NodeCloud {
  const NodeTable* table;
  std::vector<uint32_t> ids;  // valid nodes
  Eigen::Vector3d origin;
  size_t kdtree_get_point_count() const { return ids.size(); }
  double kdtree_get_pt(size_t i, size_t dim) const {
    return table->nodes[ids[i]].point_in_world[dim] - origin[dim];
  }
  template <class BBOX>
  bool kdtree_get_bbox(BBOX&) const { return false; }
};

}  // namespace

struct CorrespondenceFinder::ProximityIndex {
  using Tree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, NodeCloud>, NodeCloud, 3, uint32_t>;
  explicit ProximityIndex(const NodeTable& nodes) : cloud{&nodes, {}, Eigen::Vector3d::Zero()} {
    for (uint32_t i = 0; i < nodes.nodes.size(); ++i) {
      if (!nodes.nodes[i].valid) continue;
      if (cloud.ids.empty()) cloud.origin = nodes.nodes[i].point_in_world;
      cloud.ids.push_back(i);
      mean_gsd += nodes.nodes[i].gsd_m;
    }
    if (cloud.ids.empty()) return;
    mean_gsd /= cloud.ids.size();
    tree = std::make_unique<Tree>(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    tree->buildIndex();
  }
  NodeCloud cloud;
  double mean_gsd = 0.0;
  std::unique_ptr<Tree> tree;  // none without valid nodes
};

CorrespondenceFinder::CorrespondenceFinder(const std::vector<SacView>& views, const NodeTable& nodes,
                                           const std::vector<std::vector<uint32_t>>& neighbors,
                                           const SacOptions& options, const std::vector<double>& noise_factor)
    : views_(views), nodes_(nodes), neighbors_(neighbors), options_(options), noise_factor_(noise_factor) {
  if (options.correspondence == "proximity") {
    proximity_ = std::make_unique<ProximityIndex>(nodes);
    stride_ = static_cast<size_t>(options.max_neighbor_views);
    return;
  }
  if (options.correspondence == "dense") {
    for (const auto& v : views) {
      if (v.consistency == nullptr || v.consistency->empty()) {
        throw Error("fusion.correspondence = dense, but view " + v.view.name +
                    " has no dense-matching consistency graph (COLMAP stereo/consistency_graphs); use reprojection "
                    "or proximity");
      }
    }
  }
  for (const auto& n : neighbors) stride_ = std::max(stride_, n.size());
  if (options.correspondence == "dense") stride_ = std::max(stride_, static_cast<size_t>(options.max_neighbor_views));
}

CorrespondenceFinder::~CorrespondenceFinder() = default;

void CorrespondenceFinder::Find(uint32_t i, uint32_t* out) const {
  std::fill(out, out + stride_, kNoCorrespondent);
  const SacNode& node = nodes_.nodes[i];
  if (!node.valid) return;
  if (proximity_ != nullptr) {
    if (proximity_->tree == nullptr) return;
    const double radius = options_.proximity_radius_m > 0
                              ? options_.proximity_radius_m
                              : 1.5 * options_.superpixels.region_size_px * proximity_->mean_gsd;
    const Eigen::Vector3d q = node.point_in_world - proximity_->cloud.origin;
    std::vector<std::pair<uint32_t, double>> hits;
    proximity_->tree->radiusSearch(q.data(), radius * radius, hits, nanoflann::SearchParams(32, 0, /*sorted=*/true));
    // Nearest node of each other view, views ranked by that distance (ties by view index via stable order).
    std::vector<std::pair<double, uint32_t>> best;  // (distance^2, node id)
    std::vector<uint32_t> seen_views;
    for (const auto& [idx, dist2] : hits) {
      const uint32_t id = proximity_->cloud.ids[idx];
      const uint32_t v = nodes_.nodes[id].view;
      if (v == node.view || std::find(seen_views.begin(), seen_views.end(), v) != seen_views.end()) continue;
      seen_views.push_back(v);
      best.emplace_back(dist2, id);
    }
    std::stable_sort(best.begin(), best.end());
    for (size_t k = 0; k < best.size() && k < stride_; ++k) out[k] = best[k].second;
    return;
  }
  if (options_.correspondence != "dense") {
    const double sigma_a =
        noise_factor_.empty() ? 0.0 : DepthSigmaM(views_, noise_factor_, node.view, node.depth_m);
    for (size_t k = 0; k < neighbors_[node.view].size(); ++k) {
      const uint32_t b = neighbors_[node.view][k];
      out[k] = NodeAtProjection(views_[b], b, node.point_in_world, nodes_, options_, /*depth_test=*/true,
                                noise_factor_, sigma_a);
    }
    return;
  }
  // Dense matching: the consistency graph at the centroid pixel names the views; trust it (no depth test).
  const SacView& own = views_[node.view];
  const auto& cluster = own.superpixels->clusters[node.cluster];
  const int row = std::clamp(static_cast<int>(cluster.centroid_row), 0, own.consistency->height - 1);
  const int col = std::clamp(static_cast<int>(cluster.centroid_col), 0, own.consistency->width - 1);
  const auto [first, last] = own.consistency->At(row, col);
  size_t k = 0;
  for (const uint32_t* it = first; it != last && k < stride_; ++it) {
    const uint32_t b = *it;
    if (b >= views_.size() || b == node.view) continue;
    out[k++] = NodeAtProjection(views_[b], b, node.point_in_world, nodes_, options_, /*depth_test=*/false);
  }
}

Correspondences FindCorrespondences(const CorrespondenceFinder& finder, size_t num_nodes) {
  const size_t stride = finder.stride();
  std::vector<uint32_t> scratch(num_nodes * stride);
  tbb::parallel_for(size_t{0}, num_nodes,
                    [&](size_t i) { finder.Find(static_cast<uint32_t>(i), &scratch[i * stride]); });
  Correspondences out;
  out.offsets.resize(num_nodes + 1, 0);
  for (size_t i = 0; i < num_nodes; ++i) {
    uint32_t count = 0;
    for (size_t k = 0; k < stride; ++k) count += scratch[i * stride + k] != CorrespondenceFinder::kNoCorrespondent;
    out.offsets[i + 1] = out.offsets[i] + count;
  }
  out.node_ids.reserve(out.offsets.back());
  for (size_t i = 0; i < num_nodes * stride; ++i) {
    if (scratch[i] != CorrespondenceFinder::kNoCorrespondent) out.node_ids.push_back(scratch[i]);
  }
  return out;
}

Correspondences FindCorrespondences(const std::vector<SacView>& views, const NodeTable& nodes,
                                    const std::vector<std::vector<uint32_t>>& neighbors, const SacOptions& options,
                                    const std::vector<double>& noise_factor) {
  return FindCorrespondences(CorrespondenceFinder(views, nodes, neighbors, options, noise_factor),
                             nodes.nodes.size());
}

}  // namespace sacfuse
