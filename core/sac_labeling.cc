#include "core/sac_labeling.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "core/mrf.h"
#include "core/sac_tolerance.h"

namespace sacfuse {
namespace {

// Node-independent cost of each member's view as the Netlet's label (quality + agreement).
std::vector<double> LabelBaseCosts(const std::vector<SacView>& views, const NodeTable& nodes, const uint32_t* members,
                                   size_t n, const SacOptions& options) {
  std::vector<double> cost(n, 0.0);
  double min_gsd = 1e300;
  for (size_t k = 0; k < n; ++k) min_gsd = std::min<double>(min_gsd, nodes.nodes[members[k]].gsd_m);
  for (size_t k = 0; k < n; ++k) {
    const SacNode& label_node = nodes.nodes[members[k]];
    size_t agree = 0;
    for (size_t m = 0; m < n; ++m) {
      if (m == k) continue;
      const SacView& other = views[nodes.nodes[members[m]].view];
      agree += DepthAgreesStrictly(other, LookupDepth(other, label_node.point_in_world), options.agreement_tolerance_gsd)
                   ? 1
                   : 0;
    }
    const double agreement = n > 1 ? static_cast<double>(agree) / (n - 1) : 1.0;
    cost[k] = options.quality_weight * (label_node.gsd_m / min_gsd - 1.0) + options.agreement_weight * (1.0 - agreement);
  }
  return cost;
}

// Per view, per cluster: adjacent clusters (only needed for the smoothness term).
std::vector<std::vector<std::vector<uint32_t>>> AdjacencyPerView(const std::vector<SacView>& views) {
  std::vector<std::vector<std::vector<uint32_t>>> adj(views.size());
  tbb::parallel_for(size_t{0}, views.size(), [&](size_t v) { adj[v] = ClusterAdjacency(*views[v].superpixels); });
  return adj;
}

}  // namespace

std::vector<uint32_t> LabelNetlets(const std::vector<SacView>& views, const NodeTable& nodes, const Netlets& netlets,
                                   const SacOptions& options, LabelingStats* stats) {
  std::vector<uint32_t> chosen(nodes.nodes.size());
  for (size_t i = 0; i < nodes.nodes.size(); ++i) chosen[i] = nodes.nodes[i].view;
  const bool paper = options.unary == "paper";
  const bool smooth = !paper && options.smoothness_weight > 0 && options.smoothness_rounds > 0;
  const auto adjacency = smooth ? AdjacencyPerView(views) : std::vector<std::vector<std::vector<uint32_t>>>{};
  std::vector<uint8_t> optimal(netlets.size(), 0);

  const int rounds = 1 + (smooth ? options.smoothness_rounds : 0);
  for (int round = 0; round < rounds; ++round) {
    const std::vector<uint32_t> previous = chosen;
    tbb::parallel_for(size_t{0}, netlets.size(), [&](size_t t) {
      const size_t n = netlets.num_members(t);
      const uint32_t* members = netlets.members_of(t);
      if (n == 1) {
        optimal[t] = 1;
        return;
      }
      // Label order: by base cost (quality mode) or member order (paper mode: seed first).
      std::vector<double> base = paper ? std::vector<double>(n, 1.0) : LabelBaseCosts(views, nodes, members, n, options);
      std::vector<size_t> perm(n);
      std::iota(perm.begin(), perm.end(), 0);
      if (!paper) {
        std::stable_sort(perm.begin(), perm.end(), [&](size_t a, size_t b) {
          if (base[a] != base[b]) return base[a] < base[b];
          return nodes.nodes[members[a]].view < nodes.nodes[members[b]].view;
        });
      }
      PottsMrf mrf;
      mrf.num_nodes = static_cast<int>(n);
      mrf.num_labels = static_cast<int>(n);
      mrf.unary.resize(n * n);
      for (size_t i = 0; i < n; ++i) {
        const SacNode& node = nodes.nodes[members[i]];
        for (size_t l = 0; l < n; ++l) {
          const size_t k = perm[l];
          double u = base[k];
          if (!paper) {
            const double move = (node.point_in_world - nodes.nodes[members[k]].point_in_world).norm();
            u += options.displacement_weight * std::min(move / options.tau_m, 1.0);
            if (smooth && round > 0) {
              const auto& adj = adjacency[node.view][node.cluster];
              if (!adj.empty()) {
                size_t same = 0;
                const uint32_t label_view = nodes.nodes[members[k]].view;
                for (uint32_t c : adj) same += previous[nodes.Id(node.view, c)] == label_view ? 1 : 0;
                u -= options.smoothness_weight * static_cast<double>(same) / adj.size();
              }
            }
          }
          mrf.unary[i * n + l] = u;
        }
      }
      for (uint32_t e = netlets.edge_offsets[t]; e < netlets.edge_offsets[t + 1]; ++e) {
        const NetletEdge& edge = netlets.edges[e];
        mrf.edges.push_back({edge.i, edge.j, std::exp(-static_cast<double>(edge.distance_m))});
      }
      const MrfSolution solution = SolvePotts(mrf);
      optimal[t] = solution.proven_optimal ? 1 : 0;
      for (size_t i = 0; i < n; ++i) chosen[members[i]] = nodes.nodes[members[perm[solution.labels[i]]]].view;
    });
  }

  if (stats != nullptr) {
    *stats = LabelingStats{};
    stats->netlets = netlets.size();
    for (size_t t = 0; t < netlets.size(); ++t) {
      stats->proven_optimal += optimal[t];
      const size_t n = netlets.num_members(t);
      if (stats->size_histogram.size() <= n) stats->size_histogram.resize(n + 1, 0);
      ++stats->size_histogram[n];
    }
    for (size_t i = 0; i < nodes.nodes.size(); ++i) {
      if (!nodes.nodes[i].valid) continue;
      if (chosen[i] == nodes.nodes[i].view) {
        ++stats->nodes_keeping_own_view;
      } else {
        ++stats->nodes_relabelled;
      }
    }
  }
  return chosen;
}

}  // namespace sacfuse
