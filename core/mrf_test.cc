#include "core/mrf.h"

#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/min_cut.h"

namespace sacfuse {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

PottsMrf MakeMrf(int num_nodes, int num_labels, std::vector<double> unary, std::vector<PottsMrf::Edge> edges) {
  PottsMrf mrf;
  mrf.num_nodes = num_nodes;
  mrf.num_labels = num_labels;
  mrf.unary = std::move(unary);
  mrf.edges = std::move(edges);
  return mrf;
}

// Smoothness part of the energy.
double SmoothEnergy(const PottsMrf& mrf, const std::vector<int>& labels) {
  double sum = 0.0;
  for (const PottsMrf::Edge& e : mrf.edges) {
    if (labels[e.i] != labels[e.j]) sum += e.weight;
  }
  return sum;
}

MrfSolverOptions ExpansionOnly() {
  MrfSolverOptions options;
  options.exact_max_nodes = 0;
  options.expansion_max_sweeps = 100;  // run to convergence so the factor-2 bound applies
  return options;
}

TEST(MrfTest, StrongEdgeForcesAgreementWeakEdgeDoesNot) {
  // Node 0 prefers label 0 by 0.3, node 1 prefers label 1 by 0.2.
  const std::vector<double> unary = {0.0, 0.3, 0.2, 0.0};
  const PottsMrf strong = MakeMrf(2, 2, unary, {{0, 1, 1.0}});
  MrfSolution s = SolvePotts(strong);
  EXPECT_EQ(s.labels, (std::vector<int>{0, 0}));  // agreement at the cheaper label: 0.2 < 0.3
  EXPECT_DOUBLE_EQ(s.energy, 0.2);
  EXPECT_TRUE(s.proven_optimal);
  EXPECT_DOUBLE_EQ(s.lower_bound, s.energy);

  const PottsMrf weak = MakeMrf(2, 2, unary, {{0, 1, 0.1}});
  s = SolvePotts(weak);
  EXPECT_EQ(s.labels, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(s.energy, 0.1);
}

TEST(MrfTest, ThreeNodeChainKnownOptimum) {
  // Chain 0 - 1 - 2, labels {0, 1, 2}. Ends want 0 and 2 strongly, middle mildly wants 1.
  // Candidates: (0,0,2): 0 + 0.5 + 0 + w12=0.6 -> 1.1; (0,2,2): 0 + 0.5 + 0 + w01=0.4 -> 0.9;
  // (0,1,2): 0 + 0 + 0 + 0.4 + 0.6 = 1.0. Optimum (0,2,2) with energy 0.9.
  const PottsMrf mrf = MakeMrf(3, 3,
                               {0.0, 2.0, 2.0,  //
                                0.5, 0.0, 0.5,  //
                                2.0, 2.0, 0.0},
                               {{0, 1, 0.4}, {1, 2, 0.6}});
  const MrfSolution s = SolvePotts(mrf);
  EXPECT_EQ(s.labels, (std::vector<int>{0, 2, 2}));
  EXPECT_NEAR(s.energy, 0.9, 1e-15);
  EXPECT_EQ(SolvePottsBruteForce(mrf).labels, s.labels);
}

TEST(MrfTest, ConstantUnaryAllShareLabelZero) {
  // The paper's mode: every view equally good; connected nodes must share one view, the tie goes to label 0.
  const int n = 6, labels = 5;
  std::vector<PottsMrf::Edge> edges;
  for (int i = 0; i + 1 < n; ++i) edges.push_back({i, i + 1, std::exp(-0.3 * i)});
  edges.push_back({0, 5, 0.2});
  const PottsMrf mrf = MakeMrf(n, labels, std::vector<double>(n * labels, 1.0), edges);
  const MrfSolution s = SolvePotts(mrf);
  EXPECT_EQ(s.labels, std::vector<int>(n, 0));
  EXPECT_DOUBLE_EQ(s.energy, 6.0);
  EXPECT_TRUE(s.proven_optimal);
  // With label 0 forbidden for node 3, everything moves to label 1.
  PottsMrf forbid = mrf;
  forbid.unary[3 * labels + 0] = kInf;
  EXPECT_EQ(SolvePotts(forbid).labels, std::vector<int>(n, 1));
}

TEST(MrfTest, TiesWithinToleranceGoToLexicographicallySmallest) {
  // (0, 0) costs 0.1 + 0.2 = 0.30000000000000004 and (1, 1) costs 0.3 + 0.0 = 0.3 in floating point: a tie in
  // exact arithmetic, so the lexicographically smaller labelling (0, 0) must win in both solvers.
  const PottsMrf mrf = MakeMrf(2, 2, {0.1, 0.3, 0.2, 0.0}, {{0, 1, 10.0}});
  ASSERT_LT(mrf.Energy({1, 1}), mrf.Energy({0, 0}));
  EXPECT_EQ(SolvePotts(mrf).labels, (std::vector<int>{0, 0}));
  EXPECT_EQ(SolvePottsBruteForce(mrf).labels, (std::vector<int>{0, 0}));
  // A real difference (far above the tolerance) is not a tie.
  const PottsMrf clear = MakeMrf(2, 2, {0.1, 0.3, 0.2, -1e-9}, {{0, 1, 10.0}});
  EXPECT_EQ(SolvePotts(clear).labels, (std::vector<int>{1, 1}));
  EXPECT_EQ(SolvePottsBruteForce(clear).labels, (std::vector<int>{1, 1}));
}

TEST(MrfTest, ForbiddenLabelAvoided) {
  // Node 1 would love label 0 through its strong edges, but label 0 is forbidden for it.
  const PottsMrf mrf = MakeMrf(3, 2,
                               {0.0, 1.0,  //
                                kInf, 0.0,  //
                                0.0, 1.0},
                               {{0, 1, 5.0}, {1, 2, 5.0}});
  for (const MrfSolverOptions& options : {MrfSolverOptions{}, ExpansionOnly()}) {
    const MrfSolution s = SolvePotts(mrf, options);
    EXPECT_EQ(s.labels, (std::vector<int>{1, 1, 1}));
    EXPECT_DOUBLE_EQ(s.energy, 2.0);
  }
}

TEST(MrfTest, IsolatedNodesTakeTheirOwnMinimum) {
  const PottsMrf mrf = MakeMrf(4, 3,
                               {0.5, 0.1, 0.9,  //
                                0.0, 0.0, 0.0,  // tie: label 0
                                kInf, 0.7, 0.2,  //
                                0.3, 0.3, -1.0},
                               {});
  const MrfSolution s = SolvePotts(mrf);
  EXPECT_EQ(s.labels, (std::vector<int>{1, 0, 2, 2}));
  EXPECT_NEAR(s.energy, 0.1 + 0.0 + 0.2 - 1.0, 1e-15);
  // Many isolated nodes with fully tied unaries: 10^12 optimal labellings, must still be instant.
  const PottsMrf tied = MakeMrf(12, 10, std::vector<double>(120, 0.25), {});
  const MrfSolution t = SolvePotts(tied);
  EXPECT_EQ(t.labels, std::vector<int>(12, 0));
  EXPECT_TRUE(t.proven_optimal);
}

TEST(MrfTest, EmptyAndSingleNode) {
  const MrfSolution empty = SolvePotts(PottsMrf{});
  EXPECT_TRUE(empty.labels.empty());
  EXPECT_EQ(empty.energy, 0.0);
  const MrfSolution one = SolvePotts(MakeMrf(1, 3, {kInf, 2.0, 2.0}, {}));
  EXPECT_EQ(one.labels, std::vector<int>{1});
}

TEST(MrfTest, ValidateThrowsOnBadInput) {
  const PottsMrf good = MakeMrf(2, 2, {0.0, 1.0, 1.0, 0.0}, {{0, 1, 0.5}});
  EXPECT_NO_THROW(good.Validate());
  auto expect_bad = [](const PottsMrf& mrf) {
    EXPECT_THROW(mrf.Validate(), Error);
    EXPECT_THROW(SolvePotts(mrf), Error);
    EXPECT_THROW(SolvePottsBruteForce(mrf), Error);
  };
  PottsMrf bad = good;
  bad.unary.pop_back();
  expect_bad(bad);
  bad = good;
  bad.num_labels = -1;
  expect_bad(bad);
  bad = good;
  bad.unary[1] = std::nan("");
  expect_bad(bad);
  bad = good;
  bad.unary[1] = -kInf;
  expect_bad(bad);
  bad = good;
  bad.unary[2] = bad.unary[3] = kInf;  // every label of node 1 forbidden
  expect_bad(bad);
  bad = good;
  bad.edges[0].weight = -0.1;
  expect_bad(bad);
  bad = good;
  bad.edges[0].weight = std::nan("");
  expect_bad(bad);
  bad = good;
  bad.edges[0].weight = kInf;
  expect_bad(bad);
  bad = good;
  bad.edges[0].j = 0;  // self loop
  expect_bad(bad);
  bad = good;
  bad.edges[0].j = 2;  // out of range
  expect_bad(bad);
  bad = MakeMrf(1, 0, {}, {});  // a node with no label at all
  expect_bad(bad);
  EXPECT_THROW(good.Energy({0}), Error);
  EXPECT_THROW(good.Energy({0, 2}), Error);
  EXPECT_EQ(good.Energy({0, 1}), 0.5);
  EXPECT_EQ(MakeMrf(2, 2, {kInf, 0.0, 0.0, 0.0}, {}).Energy({0, 0}), kInf);
  // Brute force refuses huge problems.
  EXPECT_THROW(SolvePottsBruteForce(MakeMrf(8, 8, std::vector<double>(64, 0.0), {})), Error);
}

TEST(MinCutTest, SmallGraph) {
  // s=0, t=3: 0->1 (3), 0->2 (2), 1->2 (1), 1->3 (2), 2->3 (3). Max flow 5.
  MinCutGraph g;
  g.Reset(4);
  g.AddEdge(0, 1, 3.0);
  g.AddEdge(0, 2, 2.0);
  g.AddEdge(1, 2, 1.0);
  g.AddEdge(1, 3, 2.0);
  g.AddEdge(2, 3, 3.0);
  EXPECT_DOUBLE_EQ(g.MaxFlow(0, 3), 5.0);
  EXPECT_TRUE(g.OnSourceSide(0));
  EXPECT_FALSE(g.OnSourceSide(3));
  g.Reset(2);
  g.AddEdge(0, 1, kInf);
  EXPECT_THROW(g.MaxFlow(0, 1), Error);
}

// Random Netlet: 1-8 nodes, 1-6 labels, random edge sets with weights e^-d (d in [0, 2], often quantised so
// that sums tie exactly), unaries from a small set (exact ties) or continuous, some +inf (never a whole row).
PottsMrf RandomNetlet(std::mt19937_64& rng, bool allow_negative) {
  std::uniform_int_distribution<int> nodes_dist(1, 8), labels_dist(1, 6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PottsMrf mrf;
  mrf.num_nodes = nodes_dist(rng);
  mrf.num_labels = labels_dist(rng);
  // Keep the brute force affordable (the whole test < 20 s): at most 6^7 labellings.
  while (std::pow(mrf.num_labels, mrf.num_nodes) > 300000) --mrf.num_nodes;
  const int n = mrf.num_nodes, num_labels = mrf.num_labels;
  const int unary_mode = static_cast<int>(rng() % 4);  // 0: constant, 1: quantised, 2: continuous, 3: mixed
  const double constant = unit(rng);
  const double forbid_probability = (rng() % 2) ? 0.2 : 0.0;
  mrf.unary.resize(n * num_labels);
  for (int i = 0; i < n; ++i) {
    for (int l = 0; l < num_labels; ++l) {
      double u;
      switch (unary_mode) {
        case 0: u = constant; break;
        case 1: u = 0.25 * static_cast<double>(rng() % 4); break;
        case 2: u = unit(rng); break;
        default: u = (rng() % 2) ? 0.5 : unit(rng); break;
      }
      if (allow_negative && rng() % 3 == 0) u -= 1.0;
      if (unit(rng) < forbid_probability) u = kInf;
      mrf.unary[i * num_labels + l] = u;
    }
    // Keep at least one allowed label per node (a random one).
    const int keep = static_cast<int>(rng() % num_labels);
    if (mrf.unary[i * num_labels + keep] == kInf) mrf.unary[i * num_labels + keep] = 0.5;
  }
  const double edge_probability = unit(rng);
  const bool quantised = rng() % 2;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (unit(rng) >= edge_probability) continue;
      const double d = quantised ? 0.5 * static_cast<double>(rng() % 5) : 2.0 * unit(rng);
      if (rng() % 2) {
        mrf.edges.push_back({i, j, std::exp(-d)});
      } else {
        mrf.edges.push_back({j, i, std::exp(-d)});
      }
    }
  }
  // Occasionally a parallel edge.
  if (!mrf.edges.empty() && rng() % 8 == 0) mrf.edges.push_back(mrf.edges[rng() % mrf.edges.size()]);
  return mrf;
}

TEST(MrfRandomTest, BranchAndBoundEqualsBruteForceAndExpansionWithinFactorTwo) {
  std::mt19937_64 rng(20240611);
  const int kCases = 2500;
  int exact_matches = 0, expansion_optimal = 0;
  for (int c = 0; c < kCases; ++c) {
    const bool allow_negative = c % 5 == 4;
    const PottsMrf mrf = RandomNetlet(rng, allow_negative);
    SCOPED_TRACE("case " + std::to_string(c) + ": " + std::to_string(mrf.num_nodes) + " nodes, " +
                 std::to_string(mrf.num_labels) + " labels, " + std::to_string(mrf.edges.size()) + " edges");
    const MrfSolution brute = SolvePottsBruteForce(mrf);
    const MrfSolution exact = SolvePotts(mrf);
    ASSERT_TRUE(exact.proven_optimal);
    ASSERT_EQ(exact.labels, brute.labels);
    ASSERT_EQ(exact.energy, brute.energy);
    ASSERT_EQ(exact.lower_bound, exact.energy);
    ++exact_matches;

    const MrfSolution expansion = SolvePotts(mrf, ExpansionOnly());
    ASSERT_FALSE(expansion.proven_optimal);
    ASSERT_TRUE(std::isfinite(expansion.energy));  // never a forbidden label
    ASSERT_EQ(expansion.energy, mrf.Energy(expansion.labels));
    const double tol = mrf.TieTolerance() + 1e-12;
    ASSERT_LE(expansion.lower_bound, brute.energy + tol);
    // Boykov et al., Thm 6.1 for Potts: E(y) <= E_data(y*) + 2 E_smooth(y*), i.e. <= 2 E(y*) when E_data >= 0.
    ASSERT_LE(expansion.energy, brute.energy + SmoothEnergy(mrf, brute.labels) + tol);
    if (!allow_negative) {
      ASSERT_LE(expansion.energy, 2.0 * brute.energy + tol);
    }
    if (expansion.energy <= brute.energy + tol) ++expansion_optimal;
  }
  EXPECT_EQ(exact_matches, kCases);
  std::printf("[ info ] %d/%d random Netlets: B&B == brute force; alpha-expansion optimal in %d\n", exact_matches,
              kCases, expansion_optimal);
}

TEST(MrfRandomTest, BudgetFallbackIsValid) {
  // A tiny budget forces the fallback after partial search: still feasible, bound valid, not proven.
  std::mt19937_64 rng(7);
  MrfSolverOptions options;
  options.exact_max_expansions = 3;
  int fallbacks = 0;
  for (int c = 0; c < 300; ++c) {
    const PottsMrf mrf = RandomNetlet(rng, c % 2 == 0);
    const MrfSolution brute = SolvePottsBruteForce(mrf);
    const MrfSolution s = SolvePotts(mrf, options);
    ASSERT_TRUE(std::isfinite(s.energy));
    ASSERT_EQ(s.energy, mrf.Energy(s.labels));
    ASSERT_GE(s.energy, brute.energy - mrf.TieTolerance());
    ASSERT_LE(s.lower_bound, brute.energy + mrf.TieTolerance());
    if (s.proven_optimal) {
      ASSERT_NEAR(s.energy, brute.energy, mrf.TieTolerance());
    } else {
      ++fallbacks;
    }
  }
  EXPECT_GT(fallbacks, 0);
}

TEST(MrfRandomTest, SameResultsFromSeveralThreads) {
  // Workspaces are thread-local; solving the same Netlets concurrently must give identical results.
  std::mt19937_64 rng(31);
  std::vector<PottsMrf> netlets;
  for (int c = 0; c < 400; ++c) netlets.push_back(RandomNetlet(rng, c % 2 == 0));
  std::vector<MrfSolution> reference;
  for (const PottsMrf& mrf : netlets) reference.push_back(SolvePotts(mrf));
  const int kThreads = 4;
  std::vector<std::vector<MrfSolution>> results(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      // Each thread walks the Netlets in a different rotation so workspaces see different histories.
      results[t].resize(netlets.size());
      for (size_t k = 0; k < netlets.size(); ++k) {
        const size_t idx = (k + 97 * t) % netlets.size();
        results[t][idx] = SolvePotts(netlets[idx]);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) {
    for (size_t k = 0; k < netlets.size(); ++k) {
      ASSERT_EQ(results[t][k].labels, reference[k].labels) << "thread " << t << ", Netlet " << k;
      ASSERT_EQ(results[t][k].energy, reference[k].energy);
    }
  }
}

TEST(MrfTest, LargeMrfUsesExpansion) {
  // 40 nodes > exact_max_nodes: alpha-expansion. A ring with two strong halves preferring different labels.
  const int n = 40, num_labels = 3;
  PottsMrf mrf;
  mrf.num_nodes = n;
  mrf.num_labels = num_labels;
  for (int i = 0; i < n; ++i) {
    const int preferred = i < n / 2 ? 1 : 2;
    for (int l = 0; l < num_labels; ++l) mrf.unary.push_back(l == preferred ? 0.0 : 1.0);
    mrf.edges.push_back({i, (i + 1) % n, 0.9});
  }
  mrf.unary[5 * num_labels + 1] = kInf;  // node 5 may not take its half's label
  const MrfSolution s = SolvePotts(mrf);
  EXPECT_FALSE(s.proven_optimal);
  EXPECT_EQ(s.energy, mrf.Energy(s.labels));
  EXPECT_LE(s.lower_bound, s.energy);
  std::vector<int> expected(n, 1);
  for (int i = n / 2; i < n; ++i) expected[i] = 2;
  EXPECT_NE(s.labels[5], 1);  // labels 0 and 2 cost the same for node 5 (1 + 2 * 0.9)
  EXPECT_NEAR(s.energy, 1.0 + 2 * 0.9 + 2 * 0.9, 1e-12);
  for (int i = 0; i < n; ++i) {
    if (i != 5) {
      EXPECT_EQ(s.labels[i], expected[i]) << i;
    }
  }
}

TEST(MrfTimingTest, TenNodesEightLabels) {
  // Not an assertion: prints solves per second for 10-node / 8-label Netlets with ~30 edges.
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 10, num_labels = 8, kNetlets = 2000;
  for (const bool constant_unary : {false, true}) {
    std::vector<PottsMrf> netlets;
    for (int k = 0; k < kNetlets; ++k) {
      PottsMrf mrf;
      mrf.num_nodes = n;
      mrf.num_labels = num_labels;
      mrf.unary.resize(n * num_labels);
      for (double& u : mrf.unary) u = constant_unary ? 1.0 : unit(rng);
      for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
          if (unit(rng) < 30.0 / 45.0) mrf.edges.push_back({i, j, std::exp(-2.0 * unit(rng))});
        }
      }
      netlets.push_back(std::move(mrf));
    }
    double checksum = 0.0;
    int proven = 0;
    const std::clock_t cpu_start = std::clock();
    const auto start = std::chrono::steady_clock::now();
    for (const PottsMrf& mrf : netlets) {
      const MrfSolution s = SolvePotts(mrf);
      checksum += s.energy;
      proven += s.proven_optimal;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    std::printf("[ info ] 10 nodes / 8 labels / ~30 edges, %s unary: %.0f solves/s per core (%.1f us CPU each, "
                "%.1f us wall), %d/%d proven, checksum %.6f\n",
                constant_unary ? "constant" : "random", kNetlets / cpu_seconds, 1e6 * cpu_seconds / kNetlets,
                1e6 * seconds / kNetlets, proven, kNetlets, checksum);
  }
}

}  // namespace
}  // namespace sacfuse
