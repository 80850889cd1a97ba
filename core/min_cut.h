#pragma once
// Tiny s-t max-flow / min-cut (Edmonds–Karp) for the binary moves of alpha-expansion (core/mrf_expansion.cc).
// Graphs have a few dozen nodes. Buffers survive Reset(), so a graph object reused for many moves does not
// allocate once it has grown to the largest size seen.
#include <vector>

namespace sacfuse {

class MinCutGraph {
 public:
  // Removes all arcs and sets the node count (nodes are 0 .. num_nodes-1).
  void Reset(int num_nodes);

  // Adds arc u->v with `capacity` and arc v->u with `reverse_capacity` (both >= 0; +infinity allowed as long as
  // no source-sink path consists of infinite arcs only, otherwise MaxFlow throws sacfuse::Error).
  void AddEdge(int u, int v, double capacity, double reverse_capacity = 0.0);

  // Maximum flow from `source` to `sink`. Afterwards OnSourceSide(v) tells whether v lies in the minimal
  // source set of a minimum cut (the nodes reachable from the source in the residual graph). Deterministic:
  // the result depends only on the arcs and their insertion order.
  double MaxFlow(int source, int sink);
  bool OnSourceSide(int v) const { return reached_[v] != 0; }

  int num_nodes() const { return num_nodes_; }

 private:
  struct Arc {
    int to = 0;
    int next = -1;  // next arc out of the same tail, -1 = end of list
    double residual = 0.0;
  };
  // Breadth-first search in the residual graph from `source`; fills reached_ and parent_arc_.
  bool FindPath(int source, int sink);

  int num_nodes_ = 0;
  std::vector<int> head_;    // first arc out of each node
  std::vector<Arc> arcs_;    // arcs 2k and 2k+1 are each other's reverse
  std::vector<int> parent_arc_;
  std::vector<int> queue_;
  std::vector<char> reached_;
};

}  // namespace sacfuse
