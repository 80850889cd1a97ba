#pragma once
// Solver for the small pairwise Potts Markov networks ("Netlets") of Select-and-Combine (paper Sec. III.B,
// Eq. 2 and 3): each node chooses a label (a view / depth map); the unary term scores the choice and every
// edge with weight w = exp(-||p_i - p_j||) costs w when its two ends choose different views.
//
// Tie breaking (deterministic, part of the contract): let E* be the minimum energy and
// tol = TieTolerance() = 1e-12 * (sum_i max_{finite l} |unary(i, l)| + sum_e weight_e), i.e. 1e-12 relative to
// the magnitude of the energy terms (the scale of floating-point rounding in any summation order). Among all
// labellings y with Energy(y) <= E* + tol the solvers return the lexicographically smallest label vector
// (node 0 first, lower label index first). Callers order the labels by preference, so ties go to the preferred
// view (in the paper's constant-unary mode, all nodes take label 0). SolvePotts (when it proves optimality)
// and SolvePottsBruteForce follow the same rule and agree exactly. The solver is single-threaded and its
// result does not depend on the number of threads callers use to solve different Netlets concurrently.
#include <cstdint>
#include <vector>

namespace sacfuse {

// Pairwise Potts MRF: E(y) = sum_i unary[i * num_labels + y_i] + sum_edges weight * [y_i != y_j].
struct PottsMrf {
  int num_nodes = 0;
  int num_labels = 0;
  std::vector<double> unary;  // num_nodes x num_labels, row-major; +infinity = label forbidden for that node
  struct Edge {
    int i = 0, j = 0;
    double weight = 0.0;
  };  // weight >= 0 and finite, i != j; parallel edges add up
  std::vector<Edge> edges;

  // Sums the unaries in node order, then the cut edge weights in edge order. +infinity if a forbidden label is
  // used. Throws sacfuse::Error if `labels` has the wrong size or a label out of range.
  double Energy(const std::vector<int>& labels) const;
  // Throws sacfuse::Error on inconsistent sizes, NaN or -infinity unaries, bad edge ends, negative / NaN /
  // infinite weights, or a node for which every label is forbidden.
  void Validate() const;
  // Absolute energy tolerance under which two labellings count as tied (see the top of this file).
  double TieTolerance() const;
};

struct MrfSolution {
  std::vector<int> labels;
  double energy = 0.0;          // Energy(labels)
  bool proven_optimal = false;  // true when exact search completed (then lower_bound == energy)
  double lower_bound = 0.0;     // valid lower bound on the minimum energy
};

struct MrfSolverOptions {
  // Branch and bound up to this many nodes. Netlets have 2-12 nodes; at 16 nodes and 10 labels the worst-case
  // tree is already 1e16 leaves, and bigger problems (merged Netlets) are better served by alpha-expansion.
  // Set to 0 to force alpha-expansion.
  int exact_max_nodes = 16;
  // B&B search-node budget (~0.1 s of work at most); when exceeded, fall back to alpha-expansion.
  uint64_t exact_max_expansions = 2000000;
  // Alpha-expansion stops after this many sweeps over all labels (it usually converges in 2-3).
  int expansion_max_sweeps = 10;
};

// Exact branch and bound for num_nodes <= exact_max_nodes (proven_optimal = true, tie rule above). Beyond that
// or beyond the budget: alpha-expansion (Boykov–Veksler–Zabih), at most twice the optimum for Potts with
// non-negative unaries, deterministic but without the lexicographic tie guarantee; proven_optimal = false and
// lower_bound is a valid bound. Forbidden labels are never chosen. Validates its input (throws
// sacfuse::Error). In the extremely rare case that the budget runs out only while looking for the
// lexicographically smallest among optimal labellings, an optimal (proven) labelling is returned that may
// not be the lexicographically smallest.
MrfSolution SolvePotts(const PottsMrf& mrf, const MrfSolverOptions& options = {});

// Exhaustive enumeration with the same tie rule; throws sacfuse::Error if num_labels^num_nodes > 1e7.
MrfSolution SolvePottsBruteForce(const PottsMrf& mrf);

// Alpha-expansion from `labels` (which must use allowed labels only), improving it in place; each binary move
// is solved exactly by min-cut and accepted only if it lowers the energy by more than 0.1 * TieTolerance().
// Sweeps over the labels in increasing order. Returns Energy(*labels). Used by SolvePotts; expects a
// validated MRF.
double ImprovePottsByAlphaExpansion(const PottsMrf& mrf, int max_sweeps, std::vector<int>* labels);

}  // namespace sacfuse
