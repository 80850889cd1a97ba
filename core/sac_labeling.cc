#include "core/sac_labeling.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "core/cluster_adjacency.h"
#include "core/mrf.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

constexpr double kCostQuantum = 1e-3;

// The candidate labels of a Netlet: its distinct views in member order, each with a representative member (the
// first of that view: the seed, or a phase-1 correspondent).
struct NetletLabels {
  std::vector<uint32_t> views;
  std::vector<size_t> representative;
};

NetletLabels DistinctViews(const NodeTable& nodes, const uint32_t* members, size_t n) {
  NetletLabels labels;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t v = nodes.nodes[members[k]].view;
    if (std::find(labels.views.begin(), labels.views.end(), v) == labels.views.end()) {
      labels.views.push_back(v);
      labels.representative.push_back(k);
    }
  }
  return labels;
}

// Node-independent cost of each candidate view as a label (quality + agreement).
std::vector<double> LabelBaseCosts(const std::vector<SacView>& views, const NodeTable& nodes, const uint32_t* members,
                                   const NetletLabels& labels, const SacOptions& options) {
  const size_t num_labels = labels.views.size();
  std::vector<double> cost(num_labels, 0.0);
  // Surface normal of the Netlet: the sum of the members' plane-fit normals (all face the cameras that see them).
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  for (size_t l = 0; l < num_labels; ++l) normal += nodes.nodes[members[labels.representative[l]]].normal_in_world;
  const bool has_normal = normal.squaredNorm() > 1e-6f;
  if (has_normal) normal.normalize();
  // Expected depth uncertainty of each view here: z^2 / f, divided by the cosine of the incidence angle
  // (foreshortening: matching degrades on surfaces seen at grazing angles).
  std::vector<double> sigma(num_labels);
  double min_sigma = 1e300;
  for (size_t l = 0; l < num_labels; ++l) {
    const SacNode& r = nodes.nodes[members[labels.representative[l]]];
    const double cos_incidence = has_normal ? std::abs(normal.dot(r.ray_in_world)) : 1.0;
    sigma[l] = r.sigma_rel / std::max(cos_incidence, options.min_incidence_cos);
    min_sigma = std::min(min_sigma, sigma[l]);
  }
  for (size_t l = 0; l < num_labels; ++l) {
    const SacNode& label_node = nodes.nodes[members[labels.representative[l]]];
    size_t agree = 0;
    for (size_t m = 0; m < num_labels; ++m) {
      if (m == l) continue;
      const SacView& other = views[labels.views[m]];
      agree += DepthAgreesStrictly(other, LookupDepth(other, label_node.point_in_world), options.agreement_tolerance_gsd)
                   ? 1
                   : 0;
    }
    const double agreement = num_labels > 1 ? static_cast<double>(agree) / (num_labels - 1) : 1.0;
    cost[l] = options.quality_weight * (sigma[l] / min_sigma - 1.0) +
              options.agreement_weight * (1.0 - agreement);
    // Differences below kCostQuantum are rounding noise (e.g. incidence angles of parallel views): quantising
    // makes such views tie exactly, so the tie rule (lowest view index) decides alike in every Netlet.
    cost[l] = std::round(cost[l] / kCostQuantum) * kCostQuantum;
  }
  return cost;
}

// Per view, per cluster: adjacent clusters (only needed for the smoothness term).
std::vector<std::vector<std::vector<uint32_t>>> AdjacencyPerView(const std::vector<SacView>& views) {
  std::vector<std::vector<std::vector<uint32_t>>> adj(views.size());
  tbb::parallel_for(size_t{0}, views.size(), [&](size_t v) { adj[v] = ClusterAdjacency(*views[v].superpixels); });
  return adj;
}

// The cross-Netlet smoothness of a round after the first: the previous round's labels and each view's cluster
// adjacency. Null: none (the first round, or the smoothness is off).
struct Smoothing {
  const std::vector<uint32_t>* previous = nullptr;
  const std::vector<std::vector<std::vector<uint32_t>>>* adjacency = nullptr;
};

// Solves Netlet t: writes the label of each of its first `decided` members to labels[0, decided) and tells whether
// the solution is proven optimal. A Netlet whose members all come from one view keeps it (proven).
bool SolveNetlet(const std::vector<SacView>& views, const NodeTable& nodes, const Netlets& netlets, size_t t,
                 const SacOptions& options, const Smoothing& smoothing, size_t decided, uint32_t* labels) {
  const size_t n = netlets.num_members(t);
  const uint32_t* members = netlets.members_of(t);
  const NetletLabels candidates = DistinctViews(nodes, members, n);
  const size_t num_labels = candidates.views.size();
  if (num_labels == 1) {
    for (size_t i = 0; i < decided; ++i) labels[i] = candidates.views[0];
    return true;
  }
  const bool paper = options.unary == "paper";
  // Label order: by base cost, then view index (quality); by view index alone (paper: every labelling with one
  // shared label ties, and the same rule in every overlapping Netlet makes the choices agree).
  const std::vector<double> base = paper ? std::vector<double>(num_labels, 1.0)
                                         : LabelBaseCosts(views, nodes, members, candidates, options);
  std::vector<size_t> perm(num_labels);
  std::iota(perm.begin(), perm.end(), 0);
  std::stable_sort(perm.begin(), perm.end(), [&](size_t a, size_t b) {
    if (base[a] != base[b]) return base[a] < base[b];
    return candidates.views[a] < candidates.views[b];
  });
  PottsMrf mrf;
  mrf.num_nodes = static_cast<int>(n);
  mrf.num_labels = static_cast<int>(num_labels);
  mrf.unary.resize(n * num_labels);
  for (size_t i = 0; i < n; ++i) {
    const SacNode& node = nodes.nodes[members[i]];
    for (size_t l = 0; l < num_labels; ++l) {
      const uint32_t label_view = candidates.views[perm[l]];
      double u = base[perm[l]];
      if (!paper) {
        double move = 1e300;  // to the nearest member of the label's view
        for (size_t m = 0; m < n; ++m) {
          if (nodes.nodes[members[m]].view == label_view) {
            move = std::min(move, (node.point_in_world - nodes.nodes[members[m]].point_in_world).norm());
          }
        }
        u += options.displacement_weight * std::min(move / options.tau_m, 1.0);
        if (smoothing.previous != nullptr) {
          const auto& adj = (*smoothing.adjacency)[node.view][node.cluster];
          if (!adj.empty()) {
            size_t same = 0;
            for (uint32_t c : adj) same += (*smoothing.previous)[nodes.Id(node.view, c)] == label_view ? 1 : 0;
            u -= options.smoothness_weight * static_cast<double>(same) / adj.size();
          }
        }
      }
      mrf.unary[i * num_labels + l] = u;
    }
  }
  for (uint32_t e = netlets.edge_offsets[t]; e < netlets.edge_offsets[t + 1]; ++e) {
    const NetletEdge& edge = netlets.edges[e];
    mrf.edges.push_back({edge.i, edge.j, std::exp(-static_cast<double>(edge.distance_m))});
  }
  const MrfSolution solution = SolvePotts(mrf);
  for (size_t i = 0; i < decided; ++i) labels[i] = candidates.views[perm[solution.labels[i]]];
  return solution.proven_optimal;
}

bool SmoothingOn(const SacOptions& options) {
  return options.unary != "paper" && options.smoothness_weight > 0 && options.smoothness_rounds > 0;
}

void CountLabel(const NodeTable& nodes, uint32_t node, uint32_t label, LabelingStats* stats) {
  if (!nodes.nodes[node].valid) return;
  if (label == nodes.nodes[node].view) {
    ++stats->nodes_keeping_own_view;
  } else {
    ++stats->nodes_relabelled;
  }
}

void CountNetlet(size_t members, bool proven_optimal, LabelingStats* stats) {
  ++stats->netlets;
  stats->proven_optimal += proven_optimal ? 1 : 0;
  if (stats->size_histogram.size() <= members) stats->size_histogram.resize(members + 1, 0);
  ++stats->size_histogram[members];
}

}  // namespace

std::vector<uint32_t> LabelNetlets(const std::vector<SacView>& views, const NodeTable& nodes, const Netlets& netlets,
                                   const SacOptions& options, LabelingStats* stats) {
  std::vector<uint32_t> chosen(nodes.nodes.size());
  for (size_t i = 0; i < nodes.nodes.size(); ++i) chosen[i] = nodes.nodes[i].view;
  const bool smooth = SmoothingOn(options);
  const auto adjacency = smooth ? AdjacencyPerView(views) : std::vector<std::vector<std::vector<uint32_t>>>{};
  std::vector<uint8_t> optimal(netlets.size(), 0);
  // Per-node Netlets decide their centre only; partitions decide every member.
  const bool per_node = options.netlets == "node";

  const int rounds = 1 + (smooth ? options.smoothness_rounds : 0);
  for (int round = 0; round < rounds; ++round) {
    const std::vector<uint32_t> previous = chosen;
    const Smoothing smoothing = round > 0 ? Smoothing{&previous, &adjacency} : Smoothing{};
    tbb::parallel_for(size_t{0}, netlets.size(), [&](size_t t) {
      const size_t decided = per_node ? 1 : netlets.num_members(t);
      std::vector<uint32_t> labels(decided);
      optimal[t] = SolveNetlet(views, nodes, netlets, t, options, smoothing, decided, labels.data()) ? 1 : 0;
      const uint32_t* members = netlets.members_of(t);
      for (size_t i = 0; i < decided; ++i) chosen[members[i]] = labels[i];
    });
  }

  if (stats != nullptr) {
    *stats = LabelingStats{};
    for (size_t t = 0; t < netlets.size(); ++t) CountNetlet(netlets.num_members(t), optimal[t] != 0, stats);
    for (uint32_t i = 0; i < nodes.nodes.size(); ++i) CountLabel(nodes, i, chosen[i], stats);
    stats->labelled_nodes = nodes.num_valid();
  }
  return chosen;
}

NodeLabels::NodeLabels(const std::vector<SacView>& views, const NodeTable& nodes, const CorrespondenceFinder& finder,
                       const SacOptions& options) {
  if (options.netlets != "node" || SmoothingOn(options)) {
    const Correspondences correspondences = FindCorrespondences(finder, nodes.nodes.size());
    const Netlets netlets = options.netlets == "node" ? BuildNodeNetlets(nodes, correspondences, options.tau_m)
                                                      : BuildNetlets(nodes, correspondences, options.tau_m);
    LabelingStats stats;
    const std::vector<uint32_t> chosen = LabelNetlets(views, nodes, netlets, options, &stats);
    stats.correspondences = correspondences.node_ids.size();
    *this = NodeLabels(chosen, std::move(stats));
    return;
  }
  views_ = &views;
  nodes_ = &nodes;
  finder_ = &finder;
  options_ = &options;
  on_demand_ = true;
  const size_t n = nodes.nodes.size();
  labels_ = std::make_unique<std::atomic<uint32_t>[]>(n);
  netlets_ = std::make_unique<std::atomic<uint32_t>[]>(n);
  // A node without a Netlet (invalid depth) keeps its own view.
  for (size_t i = 0; i < n; ++i) labels_[i] = nodes.nodes[i].valid ? 0 : kSolved | nodes.nodes[i].view;
}

NodeLabels::NodeLabels(const std::vector<uint32_t>& chosen_view, LabelingStats stats)
    : solved_stats_(std::move(stats)), labels_(std::make_unique<std::atomic<uint32_t>[]>(chosen_view.size())) {
  for (size_t i = 0; i < chosen_view.size(); ++i) labels_[i] = kSolved | chosen_view[i];
}

uint32_t NodeLabels::Solve(uint32_t node) const {
  const NodeTable& nodes = *nodes_;
  std::vector<uint32_t> found(finder_->stride());
  finder_->Find(node, found.data());
  const size_t num_found = static_cast<size_t>(
      std::remove(found.begin(), found.end(), CorrespondenceFinder::kNoCorrespondent) - found.begin());
  const Netlets netlet = NetletsFromGroups(
      nodes, {NodeNetletMembers(nodes, node, found.data(), found.data() + num_found, options_->tau_m)},
      options_->tau_m);
  uint32_t label = 0;
  const bool optimal = SolveNetlet(*views_, nodes, netlet, 0, *options_, Smoothing{}, 1, &label);
  // Two threads may solve the same node at once; both store the same values.
  netlets_[node].store(static_cast<uint32_t>(netlet.num_members(0) << 16 | num_found << 1 | (optimal ? 1 : 0)),
                       std::memory_order_relaxed);
  labels_[node].store(kSolved | label, std::memory_order_relaxed);
  return label;
}

LabelingStats NodeLabels::Stats() const {
  if (!on_demand_) return solved_stats_;
  const NodeTable& nodes = *nodes_;
  LabelingStats stats;
  for (uint32_t i = 0; i < nodes.nodes.size(); ++i) {
    const uint32_t label = labels_[i].load(std::memory_order_relaxed);
    if (!nodes.nodes[i].valid || (label & kSolved) == 0) continue;
    const uint32_t netlet = netlets_[i].load(std::memory_order_relaxed);
    ++stats.labelled_nodes;
    stats.correspondences += (netlet >> 1) & 0x7fff;
    CountNetlet(netlet >> 16, (netlet & 1) != 0, &stats);
    CountLabel(nodes, i, label & ~kSolved, &stats);
  }
  return stats;
}

}  // namespace sacfuse
