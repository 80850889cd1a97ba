// Netlet labelling on hand-made blocks whose optimal labels are known by construction.
#include "core/sac_labeling.h"

#include <gtest/gtest.h>

#include "core/correspondences.h"
#include "core/netlets.h"
#include "core/sac_test_scene.h"
#include "core/view_neighbors.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::kNorth;
using testing::NadirView;
using testing::PlaneDepth;
using testing::SyntheticBlock;

struct Labelled {
  NodeTable nodes;
  Netlets netlets;
  std::vector<uint32_t> chosen;
  LabelingStats stats;
};

Labelled Label(const SyntheticBlock& block, const SacOptions& options) {
  const auto views = block.SacViews();
  Labelled out;
  out.nodes = BuildNodes(views);
  const auto neighbors = SelectNeighborViews(views, out.nodes, options);
  const Correspondences corr = FindCorrespondences(views, out.nodes, neighbors, options);
  out.netlets = BuildNodeNetlets(out.nodes, corr, options.tau_m);
  out.chosen = LabelNetlets(views, out.nodes, out.netlets, options, &out.stats);
  return out;
}

// Views seen in the Netlet whose centre is `node` (per-node Netlets list the centre first).
std::vector<uint32_t> NetletViewsOf(const Labelled& l, uint32_t node) {
  for (size_t t = 0; t < l.netlets.size(); ++t) {
    if (l.netlets.members_of(t)[0] != node) continue;
    std::vector<uint32_t> views;
    for (size_t m = 0; m < l.netlets.num_members(t); ++m) views.push_back(l.nodes.nodes[l.netlets.members_of(t)[m]].view);
    return views;
  }
  return {};
}

SacOptions Options() {
  SacOptions o;
  o.superpixels.region_size_px = 6;
  return o;
}

// Two views of a plane, view 0 from half the height (half the GSD, a quarter of z^2/f): every Netlet that holds
// both views must label its centre 0, whichever view the centre comes from; Netlets of one view keep it.
TEST(SacLabelingTest, TwoViewNetletsSelectTheFinerView) {
  SyntheticBlock block;
  const View fine = NadirView(0, kEast, kNorth, 250.0), coarse = NadirView(1, kEast + 4.0, kNorth, 500.0);
  block.Add(fine, PlaneDepth(fine));
  block.Add(coarse, PlaneDepth(coarse));
  const Labelled l = Label(block, Options());
  size_t two_view = 0;
  for (uint32_t i = 0; i < l.nodes.nodes.size(); ++i) {
    if (!l.nodes.nodes[i].valid) continue;
    const auto views = NetletViewsOf(l, i);
    const bool both = std::find(views.begin(), views.end(), 0u) != views.end() &&
                      std::find(views.begin(), views.end(), 1u) != views.end();
    if (both) {
      ++two_view;
      EXPECT_EQ(l.chosen[i], 0u) << "node " << i << " of view " << l.nodes.nodes[i].view;
    } else {
      EXPECT_EQ(l.chosen[i], l.nodes.nodes[i].view) << "node " << i;
    }
  }
  EXPECT_GT(two_view, 100u);
  EXPECT_EQ(l.stats.proven_optimal, l.stats.netlets);
}

// Three equal views, view 1 biased by 0.6 m (3.6 GSD: inside the correspondence tolerance, outside the agreement
// tolerance). Optimal labelling of every three-view Netlet: the shared label of the two agreeing views, the lower
// index on their tie, i.e. view 0 — also for the centres from views 1 and 2.
TEST(SacLabelingTest, ThreeViewNetletsAvoidTheBiasedViewAndBreakTiesByIndex) {
  SyntheticBlock block;
  for (int i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + 1.0 * i, kNorth, 500.0);
    block.Add(v, PlaneDepth(v, i == 1 ? 0.6 : 0.0));
  }
  SacOptions options = Options();
  options.depth_tolerance_gsd = 5.0;
  const Labelled l = Label(block, options);
  size_t three_view = 0;
  for (uint32_t i = 0; i < l.nodes.nodes.size(); ++i) {
    if (!l.nodes.nodes[i].valid) continue;
    auto views = NetletViewsOf(l, i);
    std::sort(views.begin(), views.end());
    if (views == std::vector<uint32_t>{0, 1, 2}) {
      ++three_view;
      EXPECT_EQ(l.chosen[i], 0u) << "node " << i << " of view " << l.nodes.nodes[i].view;
    }
    if (views.size() > 1) {
      EXPECT_NE(l.chosen[i], 1u) << "the biased view was selected for node " << i;
    }
  }
  EXPECT_GT(three_view, 50u);
}

// The paper's constant unary: every Netlet's labelling ties; the lowest view index wins everywhere.
TEST(SacLabelingTest, PaperUnaryTiesGoToTheLowestViewIndex) {
  SyntheticBlock block;
  for (int i = 0; i < 3; ++i) {
    const View v = NadirView(2 - i, kEast + 1.5 * i, kNorth, 500.0);  // indices not in position order
    block.Add(v, PlaneDepth(v));
  }
  SacOptions options = Options();
  options.unary = "paper";
  const Labelled l = Label(block, options);
  for (uint32_t i = 0; i < l.nodes.nodes.size(); ++i) {
    if (!l.nodes.nodes[i].valid) continue;
    const auto views = NetletViewsOf(l, i);
    EXPECT_EQ(l.chosen[i], *std::min_element(views.begin(), views.end())) << "node " << i;
  }
}

// NodeLabels with the defaults solves a node's Netlet only when its label is asked for, and gives LabelNetlets'
// label; its statistics count only the nodes asked for. Partition Netlets are all solved at once.
TEST(SacLabelingTest, NodeLabelsOnDemandAreLabelNetletsLabels) {
  SyntheticBlock block;
  for (int i = 0; i < 3; ++i) {
    const View v = NadirView(i, kEast + 1.0 * i, kNorth, 250.0 + 125.0 * i);
    block.Add(v, PlaneDepth(v, i == 1 ? 0.6 : 0.0));
  }
  SacOptions options = Options();
  options.depth_tolerance_gsd = 5.0;
  const Labelled l = Label(block, options);
  const auto views = block.SacViews();
  const auto neighbors = SelectNeighborViews(views, l.nodes, options);
  const CorrespondenceFinder finder(views, l.nodes, neighbors, options);
  const NodeLabels labels(views, l.nodes, finder, options);
  ASSERT_TRUE(labels.on_demand());
  EXPECT_EQ(labels.Stats().labelled_nodes, 0u);
  const Correspondences every = FindCorrespondences(finder, l.nodes.nodes.size());
  size_t asked = 0, relabelled = 0, correspondents = 0;
  for (uint32_t i = 0; i < l.nodes.nodes.size(); i += 2) {  // every second node
    EXPECT_EQ(labels.At(i), l.chosen[i]) << "node " << i;
    EXPECT_EQ(labels.At(i), l.chosen[i]) << "node " << i << ", asked again";
    if (!l.nodes.nodes[i].valid) continue;
    ++asked;
    relabelled += l.chosen[i] != l.nodes.nodes[i].view ? 1 : 0;
    correspondents += every.count(i);
  }
  const LabelingStats stats = labels.Stats();
  EXPECT_GT(relabelled, 10u);
  EXPECT_EQ(stats.labelled_nodes, asked);
  EXPECT_EQ(stats.netlets, asked);
  EXPECT_EQ(stats.nodes_relabelled, relabelled);
  EXPECT_EQ(stats.nodes_relabelled + stats.nodes_keeping_own_view, asked);
  EXPECT_LT(stats.labelled_nodes, l.stats.labelled_nodes);
  EXPECT_EQ(stats.correspondences, correspondents);

  options.netlets = "partition";
  const NodeLabels all(views, l.nodes, finder, options);
  EXPECT_FALSE(all.on_demand());
  EXPECT_EQ(all.Stats().labelled_nodes, l.nodes.num_valid());
}

}  // namespace
}  // namespace sacfuse
