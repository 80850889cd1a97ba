#include "core/min_cut.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace sacfuse {

void MinCutGraph::Reset(int num_nodes) {
  if (num_nodes < 0) throw Error("MinCutGraph: negative node count " + std::to_string(num_nodes));
  num_nodes_ = num_nodes;
  head_.assign(num_nodes, -1);
  arcs_.clear();
  reached_.assign(num_nodes, 0);
}

void MinCutGraph::AddEdge(int u, int v, double capacity, double reverse_capacity) {
  if (u < 0 || u >= num_nodes_ || v < 0 || v >= num_nodes_ || u == v) {
    throw Error("MinCutGraph: bad arc " + std::to_string(u) + "->" + std::to_string(v) + " in a graph of " +
                std::to_string(num_nodes_) + " nodes");
  }
  if (!(capacity >= 0.0) || !(reverse_capacity >= 0.0)) {
    throw Error("MinCutGraph: negative or NaN capacity on arc " + std::to_string(u) + "->" + std::to_string(v));
  }
  arcs_.push_back(Arc{v, head_[u], capacity});
  head_[u] = static_cast<int>(arcs_.size()) - 1;
  arcs_.push_back(Arc{u, head_[v], reverse_capacity});
  head_[v] = static_cast<int>(arcs_.size()) - 1;
}

bool MinCutGraph::FindPath(int source, int sink) {
  std::fill(reached_.begin(), reached_.end(), 0);
  parent_arc_.resize(num_nodes_);
  queue_.resize(num_nodes_);
  int q_begin = 0, q_end = 0;
  queue_[q_end++] = source;
  reached_[source] = 1;
  parent_arc_[source] = -1;
  while (q_begin < q_end) {
    const int u = queue_[q_begin++];
    for (int a = head_[u]; a >= 0; a = arcs_[a].next) {
      const Arc& arc = arcs_[a];
      if (arc.residual > 0.0 && !reached_[arc.to]) {
        reached_[arc.to] = 1;
        parent_arc_[arc.to] = a;
        if (arc.to == sink) return true;
        queue_[q_end++] = arc.to;
      }
    }
  }
  return false;
}

double MinCutGraph::MaxFlow(int source, int sink) {
  if (source < 0 || source >= num_nodes_ || sink < 0 || sink >= num_nodes_ || source == sink) {
    throw Error("MinCutGraph: bad source/sink " + std::to_string(source) + "/" + std::to_string(sink));
  }
  double flow = 0.0;
  // Edmonds–Karp needs O(V E) augmentations; each one saturates its bottleneck arc exactly (r - r == 0 in
  // floating point too). The cap is only a guard against pathological rounding; the caller verifies the move.
  const size_t max_augmentations = 4 * static_cast<size_t>(num_nodes_) * (arcs_.size() + 1) + 16;
  size_t augmentations = 0;
  // When FindPath fails, reached_ holds the residual-reachable (source) side of the minimum cut.
  while (FindPath(source, sink) && augmentations++ < max_augmentations) {
    double bottleneck = std::numeric_limits<double>::infinity();
    for (int v = sink; v != source; v = arcs_[parent_arc_[v] ^ 1].to) {
      bottleneck = std::min(bottleneck, arcs_[parent_arc_[v]].residual);
    }
    if (std::isinf(bottleneck)) throw Error("MinCutGraph: source-sink path of infinite capacity");
    for (int v = sink; v != source; v = arcs_[parent_arc_[v] ^ 1].to) {
      arcs_[parent_arc_[v]].residual -= bottleneck;
      arcs_[parent_arc_[v] ^ 1].residual += bottleneck;
    }
    flow += bottleneck;
  }
  return flow;
}

}  // namespace sacfuse
