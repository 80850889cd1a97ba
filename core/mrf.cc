#include "core/mrf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace sacfuse {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTieRelative = 1e-12;
// Pruning and move acceptance use a slack of kSlackFraction * TieTolerance(): larger than the rounding
// differences between summation orders, smaller than the tie tolerance itself.
constexpr double kSlackFraction = 0.1;

// Energy without argument checks; the one summation order of the project (unaries by node, then edges).
double EnergyUnchecked(const PottsMrf& mrf, const int* labels) {
  const int num_labels = mrf.num_labels;
  double energy = 0.0;
  for (int i = 0; i < mrf.num_nodes; ++i) energy += mrf.unary[static_cast<size_t>(i) * num_labels + labels[i]];
  for (const PottsMrf::Edge& e : mrf.edges) {
    if (labels[e.i] != labels[e.j]) energy += e.weight;
  }
  return energy;
}

// Lowest-index minimum of each unary row (always an allowed label for a validated MRF).
void ArgminUnary(const PottsMrf& mrf, std::vector<int>* labels) {
  labels->assign(mrf.num_nodes, 0);
  for (int i = 0; i < mrf.num_nodes; ++i) {
    const double* row = &mrf.unary[static_cast<size_t>(i) * mrf.num_labels];
    int best = 0;
    for (int l = 1; l < mrf.num_labels; ++l) {
      if (row[l] < row[best]) best = l;
    }
    (*labels)[i] = best;
  }
}

double SumMinUnary(const PottsMrf& mrf) {
  double sum = 0.0;
  for (int i = 0; i < mrf.num_nodes; ++i) {
    const double* row = &mrf.unary[static_cast<size_t>(i) * mrf.num_labels];
    sum += *std::min_element(row, row + mrf.num_labels);
  }
  return sum;
}

// Depth-first branch and bound over nodes in a static order ("positions"). At depth d the nodes at positions
// < d are assigned. For every unassigned position q the table row cost(q, l) = unary(q, l) + total weight of
// edges from q to assigned neighbours with a label != l, so that
//   lower bound = energy of the assigned part + sum over unassigned q of min_l cost(q, l)
// (edges between two unassigned nodes are bounded by 0). Tables are stored per depth (no undo, so no
// floating-point drift), and each row keeps its minimum, argmin and second minimum so that the bound of a
// child is evaluated in O(degree) before the child is materialised.
class BranchAndBound {
 public:
  BranchAndBound() = default;

  // Sets the problem and the node order (order[p] = node at position p).
  void Prepare(const PottsMrf& mrf, const std::vector<int>& order) {
    mrf_ = &mrf;
    n_ = mrf.num_nodes;
    num_labels_ = mrf.num_labels;
    order_ = order;
    position_.assign(n_, 0);
    for (int p = 0; p < n_; ++p) position_[order_[p]] = p;
    // Aggregated weights between positions, then adjacency lists of later neighbours.
    dense_.assign(static_cast<size_t>(n_) * n_, 0.0);
    for (const PottsMrf::Edge& e : mrf.edges) {
      if (!(e.weight > 0.0)) continue;
      int a = position_[e.i], b = position_[e.j];
      if (a > b) std::swap(a, b);
      dense_[static_cast<size_t>(a) * n_ + b] += e.weight;
    }
    adj_begin_.assign(n_ + 1, 0);
    adj_pos_.clear();
    adj_weight_.clear();
    for (int p = 0; p < n_; ++p) {
      adj_begin_[p] = static_cast<int>(adj_pos_.size());
      for (int q = p + 1; q < n_; ++q) {
        const double w = dense_[static_cast<size_t>(p) * n_ + q];
        if (w > 0.0) {
          adj_pos_.push_back(q);
          adj_weight_.push_back(w);
        }
      }
    }
    adj_begin_[n_] = static_cast<int>(adj_pos_.size());
    const size_t table_size = static_cast<size_t>(n_) * num_labels_;
    table_.resize(table_size * (n_ + 1));
    row_min_.resize(static_cast<size_t>(n_) * (n_ + 1));
    row_second_.resize(row_min_.size());
    row_arg_.resize(row_min_.size());
    partial_.assign(n_ + 1, 0.0);
    path_.assign(n_, 0);
    is_neighbour_.assign(n_, 0);
    child_lb_.resize(static_cast<size_t>(n_) * num_labels_);
    child_label_.resize(child_lb_.size());
    child_count_.assign(n_, 0);
    child_current_.assign(n_, 0);
    for (int p = 0; p < n_; ++p) {
      const double* src = &mrf.unary[static_cast<size_t>(order_[p]) * num_labels_];
      std::copy(src, src + num_labels_, &table_[static_cast<size_t>(p) * num_labels_]);
      UpdateRowStats(0, p);
    }
    expansions_ = 0;
    aborted_ = false;
  }

  // Phase 1: minimum energy. Starts from the incumbent `labels` (node-indexed, energy `energy`), prunes
  // subtrees that cannot improve it by more than `slack`. Returns false if the budget ran out; then
  // `frontier_bound` is a valid lower bound on the optimum. `labels`/`energy` hold the best labelling found.
  bool Minimise(double slack, uint64_t budget, std::vector<int>* labels, double* energy, double* frontier_bound) {
    slack_ = slack;
    budget_ = budget;
    best_ = *energy;
    improved_ = false;
    best_path_.resize(n_);
    for (int p = 0; p < n_; ++p) best_path_[p] = (*labels)[order_[p]];
    MinimiseFrom(0);
    if (improved_) {
      for (int p = 0; p < n_; ++p) (*labels)[order_[p]] = best_path_[p];
      *energy = EnergyUnchecked(*mrf_, labels->data());
    }
    if (aborted_) *frontier_bound = frontier_bound_;
    return !aborted_;
  }

  // Phase 2 (order must be the identity): the lexicographically smallest labelling with
  // Energy() <= threshold, searching only labellings lexicographically <= `reference` (which qualifies).
  // Returns false if the budget ran out; otherwise `labels` receives the result.
  bool FindLexFirst(double threshold, double slack, uint64_t budget, const std::vector<int>& reference,
                    std::vector<int>* labels) {
    threshold_ = threshold;
    slack_ = slack;
    budget_ = budget;
    reference_ = &reference;
    found_ = false;
    LexFrom(0, true);
    if (aborted_ || !found_) return false;
    *labels = path_;
    return true;
  }

  uint64_t expansions() const { return expansions_; }

 private:
  double* Row(int depth, int p) {
    return &table_[(static_cast<size_t>(depth) * n_ + p) * num_labels_];
  }
  size_t StatIndex(int depth, int p) const { return static_cast<size_t>(depth) * n_ + p; }

  void UpdateRowStats(int depth, int p) {
    const double* row = Row(depth, p);
    double lo = kInf, second = kInf;
    int arg = 0;
    for (int l = 0; l < num_labels_; ++l) {
      if (row[l] < lo) {
        second = lo;
        lo = row[l];
        arg = l;
      } else if (row[l] < second) {
        second = row[l];
      }
    }
    const size_t k = StatIndex(depth, p);
    row_min_[k] = lo;
    row_second_[k] = second;
    row_arg_[k] = arg;
  }

  // Sum of row minima of unassigned positions > d that are not neighbours of position d.
  double NonNeighbourBase(int d) {
    for (int k = adj_begin_[d]; k < adj_begin_[d + 1]; ++k) is_neighbour_[adj_pos_[k]] = 1;
    double base = 0.0;
    for (int q = d + 1; q < n_; ++q) {
      if (!is_neighbour_[q]) base += row_min_[StatIndex(d, q)];
    }
    for (int k = adj_begin_[d]; k < adj_begin_[d + 1]; ++k) is_neighbour_[adj_pos_[k]] = 0;
    return base;
  }

  // Lower bound of the child "position d takes label a" (row(d, a) must be finite).
  double ChildBound(int d, int a, double base) {
    double lb = partial_[d] + Row(d, d)[a] + base;
    for (int k = adj_begin_[d]; k < adj_begin_[d + 1]; ++k) {
      const int q = adj_pos_[k];
      const size_t s = StatIndex(d, q);
      const double excluding_a = row_arg_[s] == a ? row_second_[s] : row_min_[s];
      lb += std::min(Row(d, q)[a], excluding_a + adj_weight_[k]);
    }
    return lb;
  }

  // Builds depth d+1 from depth d with position d labelled a.
  void Materialise(int d, int a) {
    const size_t row_len = static_cast<size_t>(num_labels_);
    for (int q = d + 1; q < n_; ++q) {
      std::copy(Row(d, q), Row(d, q) + row_len, Row(d + 1, q));
      const size_t from = StatIndex(d, q), to = StatIndex(d + 1, q);
      row_min_[to] = row_min_[from];
      row_second_[to] = row_second_[from];
      row_arg_[to] = row_arg_[from];
    }
    for (int k = adj_begin_[d]; k < adj_begin_[d + 1]; ++k) {
      const int q = adj_pos_[k];
      const double w = adj_weight_[k];
      double* row = Row(d + 1, q);
      for (int l = 0; l < num_labels_; ++l) {
        if (l != a) row[l] += w;
      }
      UpdateRowStats(d + 1, q);
    }
    partial_[d + 1] = partial_[d] + Row(d, d)[a];
    path_[d] = a;
  }

  bool SpendExpansion() {
    if (++expansions_ > budget_) {
      aborted_ = true;
      return false;
    }
    return true;
  }

  void MinimiseFrom(int d) {
    if (d == n_) {
      if (partial_[n_] < best_) {
        best_ = partial_[n_];
        std::copy(path_.begin(), path_.end(), best_path_.begin());
        improved_ = true;
      }
      return;
    }
    const double base = NonNeighbourBase(d);
    const double* row = Row(d, d);
    double* lbs = &child_lb_[static_cast<size_t>(d) * num_labels_];
    int* labs = &child_label_[static_cast<size_t>(d) * num_labels_];
    int count = 0;
    for (int a = 0; a < num_labels_; ++a) {
      if (row[a] == kInf) continue;
      const double lb = ChildBound(d, a, base);
      // Insertion sort by bound, stable in the label index.
      int k = count++;
      while (k > 0 && lbs[k - 1] > lb) {
        lbs[k] = lbs[k - 1];
        labs[k] = labs[k - 1];
        --k;
      }
      lbs[k] = lb;
      labs[k] = a;
    }
    child_count_[d] = count;
    for (int c = 0; c < count; ++c) {
      if (lbs[c] >= best_ - slack_) break;  // sorted: the remaining children are pruned too
      child_current_[d] = c;
      if (!SpendExpansion()) {
        // Everything before child c of the root is fully explored; the root's children are sorted by bound,
        // and pruned subtrees cannot beat best_ by more than slack.
        frontier_bound_ = std::min(best_ - slack_, child_lb_[static_cast<size_t>(child_current_[0])]);
        return;
      }
      Materialise(d, labs[c]);
      MinimiseFrom(d + 1);
      if (aborted_) return;
    }
  }

  // Returns true when the first qualifying leaf has been found (path_ holds it).
  bool LexFrom(int d, bool on_reference) {
    if (d == n_) {
      if (EnergyUnchecked(*mrf_, path_.data()) <= threshold_) {
        found_ = true;
        return true;
      }
      return false;
    }
    const double base = NonNeighbourBase(d);
    const double* row = Row(d, d);
    const int last = on_reference ? (*reference_)[d] : num_labels_ - 1;
    for (int a = 0; a <= last; ++a) {
      if (row[a] == kInf) continue;
      if (ChildBound(d, a, base) > threshold_ + slack_) continue;
      if (!SpendExpansion()) return false;
      Materialise(d, a);
      if (LexFrom(d + 1, on_reference && a == last)) return true;
      if (aborted_) return false;
    }
    return false;
  }

  const PottsMrf* mrf_ = nullptr;
  int n_ = 0;
  int num_labels_ = 0;
  std::vector<int> order_, position_;
  std::vector<double> dense_;
  std::vector<int> adj_begin_, adj_pos_;
  std::vector<double> adj_weight_;
  std::vector<double> table_;  // (n+1) depths x n positions x num_labels
  std::vector<double> row_min_, row_second_;
  std::vector<int> row_arg_;
  std::vector<double> partial_;
  std::vector<int> path_, best_path_;
  std::vector<char> is_neighbour_;
  std::vector<double> child_lb_;
  std::vector<int> child_label_, child_count_, child_current_;
  double slack_ = 0.0, best_ = kInf, threshold_ = 0.0, frontier_bound_ = -kInf;
  uint64_t budget_ = 0, expansions_ = 0;
  bool aborted_ = false, improved_ = false, found_ = false;
  const std::vector<int>* reference_ = nullptr;
};

struct SolverWorkspace {
  BranchAndBound bnb;
  std::vector<int> order, identity, labels, lex_labels;
  std::vector<double> weighted_degree, attached;
  std::vector<char> placed;
  std::vector<int> adj_begin, adj_node, cursor;  // node-space adjacency (both directions) for ICM
  std::vector<double> adj_weight, costs;
};

// Static search order: start with the node of largest weighted degree, then repeatedly the node most strongly
// connected to the nodes already placed (ties: larger weighted degree, then lower index). Nodes tightly
// coupled to assigned ones get bounds that include their edges early.
void SearchOrder(const PottsMrf& mrf, SolverWorkspace& ws) {
  const int n = mrf.num_nodes;
  ws.weighted_degree.assign(n, 0.0);
  for (const PottsMrf::Edge& e : mrf.edges) {
    ws.weighted_degree[e.i] += e.weight;
    ws.weighted_degree[e.j] += e.weight;
  }
  ws.attached.assign(n, 0.0);
  ws.placed.assign(n, 0);
  ws.order.clear();
  for (int step = 0; step < n; ++step) {
    int pick = -1;
    for (int v = 0; v < n; ++v) {
      if (ws.placed[v]) continue;
      if (pick < 0 || ws.attached[v] > ws.attached[pick] ||
          (ws.attached[v] == ws.attached[pick] && ws.weighted_degree[v] > ws.weighted_degree[pick])) {
        pick = v;
      }
    }
    ws.placed[pick] = 1;
    ws.order.push_back(pick);
    for (int k = ws.adj_begin[pick]; k < ws.adj_begin[pick + 1]; ++k) ws.attached[ws.adj_node[k]] += ws.adj_weight[k];
  }
}

void BuildNodeAdjacency(const PottsMrf& mrf, SolverWorkspace& ws) {
  const int n = mrf.num_nodes;
  ws.adj_begin.assign(n + 1, 0);
  for (const PottsMrf::Edge& e : mrf.edges) {
    ++ws.adj_begin[e.i + 1];
    ++ws.adj_begin[e.j + 1];
  }
  for (int v = 0; v < n; ++v) ws.adj_begin[v + 1] += ws.adj_begin[v];
  ws.adj_node.resize(ws.adj_begin[n]);
  ws.adj_weight.resize(ws.adj_begin[n]);
  std::vector<int>& cursor = ws.cursor;
  cursor.assign(ws.adj_begin.begin(), ws.adj_begin.end() - 1);
  for (const PottsMrf::Edge& e : mrf.edges) {
    ws.adj_node[cursor[e.i]] = e.j;
    ws.adj_weight[cursor[e.i]++] = e.weight;
    ws.adj_node[cursor[e.j]] = e.i;
    ws.adj_weight[cursor[e.j]++] = e.weight;
  }
}

// Iterated conditional modes from the per-node unary minimum: a cheap initial upper bound.
double IteratedConditionalModes(const PottsMrf& mrf, double min_gain, SolverWorkspace& ws) {
  const int n = mrf.num_nodes, num_labels = mrf.num_labels;
  ArgminUnary(mrf, &ws.labels);
  ws.costs.resize(num_labels);
  for (int sweep = 0; sweep < 10; ++sweep) {
    bool changed = false;
    for (int v = 0; v < n; ++v) {
      const double* unary = &mrf.unary[static_cast<size_t>(v) * num_labels];
      // cost(l) = unary(l) + sum_k w_k - sum_{k: label of neighbour k == l} w_k; the common sum is dropped.
      std::copy(unary, unary + num_labels, ws.costs.begin());
      for (int k = ws.adj_begin[v]; k < ws.adj_begin[v + 1]; ++k) {
        const double w = ws.adj_weight[k];
        ws.costs[ws.labels[ws.adj_node[k]]] -= w;
      }
      int best = ws.labels[v];
      for (int l = 0; l < num_labels; ++l) {
        if (ws.costs[l] < ws.costs[best] - min_gain) best = l;
      }
      if (best != ws.labels[v]) {
        ws.labels[v] = best;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return EnergyUnchecked(mrf, ws.labels.data());
}

}  // namespace

double PottsMrf::Energy(const std::vector<int>& labels) const {
  if (static_cast<int>(labels.size()) != num_nodes) {
    throw Error("PottsMrf::Energy: " + std::to_string(labels.size()) + " labels for " + std::to_string(num_nodes) +
                " nodes");
  }
  for (int i = 0; i < num_nodes; ++i) {
    if (labels[i] < 0 || labels[i] >= num_labels) {
      throw Error("PottsMrf::Energy: label " + std::to_string(labels[i]) + " of node " + std::to_string(i) +
                  " is outside [0, " + std::to_string(num_labels) + ")");
    }
  }
  return EnergyUnchecked(*this, labels.data());
}

void PottsMrf::Validate() const {
  if (num_nodes < 0 || num_labels < 0) {
    throw Error("PottsMrf: negative size (" + std::to_string(num_nodes) + " nodes, " + std::to_string(num_labels) +
                " labels)");
  }
  if (unary.size() != static_cast<size_t>(num_nodes) * static_cast<size_t>(num_labels)) {
    throw Error("PottsMrf: unary has " + std::to_string(unary.size()) + " entries, expected " +
                std::to_string(num_nodes) + " x " + std::to_string(num_labels));
  }
  for (int i = 0; i < num_nodes; ++i) {
    bool any_allowed = false;
    for (int l = 0; l < num_labels; ++l) {
      const double u = unary[static_cast<size_t>(i) * num_labels + l];
      if (std::isnan(u) || u == -kInf) {
        throw Error("PottsMrf: unary of node " + std::to_string(i) + ", label " + std::to_string(l) +
                    " is NaN or -infinity");
      }
      if (u != kInf) any_allowed = true;
    }
    if (!any_allowed) throw Error("PottsMrf: every label is forbidden for node " + std::to_string(i));
  }
  for (size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    if (e.i < 0 || e.i >= num_nodes || e.j < 0 || e.j >= num_nodes || e.i == e.j) {
      throw Error("PottsMrf: edge " + std::to_string(k) + " (" + std::to_string(e.i) + ", " + std::to_string(e.j) +
                  ") has bad ends for " + std::to_string(num_nodes) + " nodes");
    }
    if (!(e.weight >= 0.0) || e.weight == kInf) {
      throw Error("PottsMrf: edge " + std::to_string(k) + " has weight " + std::to_string(e.weight) +
                  " (must be finite and >= 0)");
    }
  }
}

double PottsMrf::TieTolerance() const {
  double scale = 0.0;
  for (int i = 0; i < num_nodes; ++i) {
    double row = 0.0;
    for (int l = 0; l < num_labels; ++l) {
      const double u = unary[static_cast<size_t>(i) * num_labels + l];
      if (std::isfinite(u)) row = std::max(row, std::abs(u));
    }
    scale += row;
  }
  for (const Edge& e : edges) scale += e.weight;
  return kTieRelative * scale;
}

MrfSolution SolvePottsBruteForce(const PottsMrf& mrf) {
  mrf.Validate();
  const int n = mrf.num_nodes;
  if (std::pow(static_cast<double>(mrf.num_labels), n) > 1e7) {
    throw Error("SolvePottsBruteForce: " + std::to_string(mrf.num_labels) + "^" + std::to_string(n) +
                " labellings exceed the limit of 1e7");
  }
  MrfSolution solution;
  std::vector<int> labels(n, 0);
  // Visits every labelling in lexicographic order (node 0 most significant). Returns false after the last.
  auto next = [&]() {
    for (int i = n - 1; i >= 0; --i) {
      if (++labels[i] < mrf.num_labels) return true;
      labels[i] = 0;
    }
    return false;
  };
  double min_energy = kInf;
  do {
    min_energy = std::min(min_energy, EnergyUnchecked(mrf, labels.data()));
  } while (next());
  const double threshold = min_energy + mrf.TieTolerance();
  std::fill(labels.begin(), labels.end(), 0);
  do {
    const double energy = EnergyUnchecked(mrf, labels.data());
    if (energy <= threshold) {
      solution.labels = labels;
      solution.energy = energy;
      break;
    }
  } while (next());
  solution.proven_optimal = true;
  solution.lower_bound = solution.energy;
  return solution;
}

MrfSolution SolvePotts(const PottsMrf& mrf, const MrfSolverOptions& options) {
  mrf.Validate();
  MrfSolution solution;
  const int n = mrf.num_nodes;
  if (n == 0) {
    solution.proven_optimal = true;
    return solution;
  }
  thread_local SolverWorkspace ws;
  const double tolerance = mrf.TieTolerance();
  const double slack = kSlackFraction * tolerance;

  if (n > options.exact_max_nodes) {
    ArgminUnary(mrf, &solution.labels);
    solution.energy = ImprovePottsByAlphaExpansion(mrf, options.expansion_max_sweeps, &solution.labels);
    solution.lower_bound = SumMinUnary(mrf);
    return solution;
  }

  // Phase 1: minimum energy by branch and bound in a connectivity-driven order, from an ICM upper bound.
  BuildNodeAdjacency(mrf, ws);
  SearchOrder(mrf, ws);
  double energy = IteratedConditionalModes(mrf, slack, ws);
  ws.bnb.Prepare(mrf, ws.order);
  double frontier_bound = -kInf;
  if (!ws.bnb.Minimise(slack, options.exact_max_expansions, &ws.labels, &energy, &frontier_bound)) {
    solution.labels = ws.labels;
    solution.energy = ImprovePottsByAlphaExpansion(mrf, options.expansion_max_sweeps, &solution.labels);
    solution.lower_bound = std::min(solution.energy, std::max(SumMinUnary(mrf), frontier_bound));
    return solution;
  }
  const uint64_t spent = ws.bnb.expansions();

  // Phase 2: the lexicographically smallest labelling within the tie tolerance of the minimum, by a search in
  // node-index order restricted to labellings lexicographically <= the phase-1 optimum.
  ws.identity.resize(n);
  for (int i = 0; i < n; ++i) ws.identity[i] = i;
  ws.bnb.Prepare(mrf, ws.identity);
  const uint64_t remaining = options.exact_max_expansions > spent ? options.exact_max_expansions - spent : 0;
  if (ws.bnb.FindLexFirst(energy + tolerance, slack, remaining, ws.labels, &ws.lex_labels)) {
    solution.labels = ws.lex_labels;
  } else {
    solution.labels = ws.labels;  // optimal, lexicographic minimality not established (budget)
  }
  solution.energy = EnergyUnchecked(mrf, solution.labels.data());
  solution.proven_optimal = true;
  solution.lower_bound = solution.energy;
  return solution;
}

}  // namespace sacfuse
