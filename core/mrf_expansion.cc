// Alpha-expansion (Boykov, Veksler, Zabih 2001) for the Potts MRF of core/mrf.h. Each expansion move "every
// node either keeps its label or switches to alpha" is a binary submodular problem solved exactly by a min-cut.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/min_cut.h"
#include "core/mrf.h"

namespace sacfuse {

namespace {

struct ExpansionWorkspace {
  MinCutGraph graph;
  std::vector<int> candidate;
};

// Builds the graph of the expansion move towards `alpha` for `current`. Node i on the source side keeps its
// label (x_i = 0), on the sink side it switches to alpha (x_i = 1). Nodes already labelled alpha are fixed.
void BuildMoveGraph(const PottsMrf& mrf, const std::vector<int>& current, int alpha, MinCutGraph& g) {
  const int n = mrf.num_nodes;
  const int num_labels = mrf.num_labels;
  const int source = n, sink = n + 1;
  g.Reset(n + 2);
  for (int i = 0; i < n; ++i) {
    if (current[i] == alpha) continue;
    const double keep = mrf.unary[static_cast<size_t>(i) * num_labels + current[i]];  // finite
    const double move = mrf.unary[static_cast<size_t>(i) * num_labels + alpha];       // +inf = forbidden
    const double base = std::min(keep, move);
    // Arc s->i is cut when i switches, i->t when it keeps.
    if (move - base > 0.0) g.AddEdge(source, i, move - base);
    if (keep - base > 0.0) g.AddEdge(i, sink, keep - base);
  }
  for (const PottsMrf::Edge& e : mrf.edges) {
    if (!(e.weight > 0.0)) continue;
    const bool fixed_i = current[e.i] == alpha, fixed_j = current[e.j] == alpha;
    if (fixed_i && fixed_j) continue;
    if (fixed_i || fixed_j) {
      // The free end pays w if it keeps its (different from alpha) label.
      g.AddEdge(fixed_i ? e.j : e.i, sink, e.weight);
    } else if (current[e.i] == current[e.j]) {
      g.AddEdge(e.i, e.j, e.weight, e.weight);  // w * [x_i != x_j]
    } else {
      // w * (1 - x_i x_j) = w * [x_j = 0] + w * [x_i = 0, x_j = 1].
      g.AddEdge(e.j, sink, e.weight);
      g.AddEdge(e.i, e.j, e.weight);
    }
  }
}

}  // namespace

double ImprovePottsByAlphaExpansion(const PottsMrf& mrf, int max_sweeps, std::vector<int>* labels) {
  if (labels == nullptr || static_cast<int>(labels->size()) != mrf.num_nodes) {
    throw Error("ImprovePottsByAlphaExpansion: initial labelling has the wrong size");
  }
  double energy = mrf.Energy(*labels);
  if (!std::isfinite(energy)) {
    throw Error("ImprovePottsByAlphaExpansion: initial labelling uses a forbidden label");
  }
  thread_local ExpansionWorkspace ws;
  const double min_gain = 0.1 * mrf.TieTolerance();
  const int n = mrf.num_nodes;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool improved = false;
    for (int alpha = 0; alpha < mrf.num_labels; ++alpha) {
      BuildMoveGraph(mrf, *labels, alpha, ws.graph);
      ws.graph.MaxFlow(n, n + 1);
      ws.candidate = *labels;
      bool changed = false;
      for (int i = 0; i < n; ++i) {
        if (ws.candidate[i] != alpha && !ws.graph.OnSourceSide(i)) {
          ws.candidate[i] = alpha;
          changed = true;
        }
      }
      if (!changed) continue;
      const double candidate_energy = mrf.Energy(ws.candidate);
      if (candidate_energy < energy - min_gain) {
        labels->swap(ws.candidate);
        energy = candidate_energy;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return energy;
}

}  // namespace sacfuse
