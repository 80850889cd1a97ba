// The views consulted per region (core/consulted_views.h) on nadir views over a plane, where which view sees which
// region is known by construction.
#include "core/consulted_views.h"

#include <vector>

#include <gtest/gtest.h>

#include "core/sac_test_scene.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::kGroundZ;
using testing::kNorth;
using testing::NadirView;
using testing::PlaneDepth;
using testing::SyntheticBlock;

// Nadir views 500 m above the plane see 20 m x 15 m (120 x 90 px, f 3000 px). View 0 is centred on the boundary
// between two 10 m regions (east kEast + [0, 10) and + [10, 20)); view 1 sees the western region whole and 2 m of
// the eastern one, view 2 the other way round.
SyntheticBlock ThreeViews() {
  SyntheticBlock block;
  const double centres_east[] = {kEast + 10.0, kEast + 2.0, kEast + 18.0};
  for (uint32_t i = 0; i < 3; ++i) {
    const View view = NadirView(i, centres_east[i], kNorth + 5.0, 500.0);
    block.Add(view, PlaneDepth(view));
  }
  return block;
}

// Valid nodes of view 0 on the ground, 1 m apart, east offsets [east_from, east_to) from kEast and north offsets
// [0.5, 9.5] from kNorth (one row of regions).
NodeTable GroundNodes(double east_from, double east_to) {
  NodeTable table;
  for (double e = east_from + 0.5; e < east_to; e += 1.0) {
    for (double n = 0.5; n < 10.0; n += 1.0) {
      SacNode node;
      node.point_in_world = {kEast + e, kNorth + n, kGroundZ};
      node.view = 0;
      node.cluster = static_cast<uint32_t>(table.nodes.size());
      node.valid = true;
      table.nodes.push_back(node);
    }
  }
  table.view_offset = {0, static_cast<uint32_t>(table.nodes.size()), static_cast<uint32_t>(table.nodes.size()),
                       static_cast<uint32_t>(table.nodes.size())};
  return table;
}

ConsultOptions OneViewPerRegion(double region_m) {
  ConsultOptions options;
  options.max_views = 1;
  options.region_m = region_m;
  return options;
}

Eigen::Vector3d Ground(double east, double north) { return {kEast + east, kNorth + north, kGroundZ}; }

TEST(ConsultedViewsTest, EachRegionConsultsTheViewThatSeesIt) {
  const SyntheticBlock block = ThreeViews();
  const auto views = block.SacViews();
  const ConsultedViews consulted = ConsultedViews::Select(views, GroundNodes(0, 20), OneViewPerRegion(10.0));
  EXPECT_EQ(consulted.At(0, Ground(3, 5)), (std::vector<uint32_t>{1}));
  EXPECT_EQ(consulted.At(0, Ground(17, 5)), (std::vector<uint32_t>{2}));
  // A region holds its western and southern edges (floor of the coordinate over the region size).
  EXPECT_EQ(consulted.At(0, Ground(10.0, 5)), (std::vector<uint32_t>{2}));
  EXPECT_EQ(consulted.At(0, Ground(9.99, 5)), (std::vector<uint32_t>{1}));
  // Beyond the view's regions: the nearest region's list.
  EXPECT_EQ(consulted.At(0, Ground(45, -30)), (std::vector<uint32_t>{2}));
  EXPECT_EQ(consulted.At(0, Ground(-45, 30)), (std::vector<uint32_t>{1}));
  // Views without nodes consult nobody.
  EXPECT_TRUE(consulted.At(1, Ground(3, 5)).empty());
  // One region for the whole view: views 1 and 2 both see 12 of its 20 m; the tie goes to the lower index.
  const ConsultedViews whole = ConsultedViews::Select(views, GroundNodes(0, 20), OneViewPerRegion(0.0));
  EXPECT_EQ(whole.At(0, Ground(17, 5)), (std::vector<uint32_t>{1}));
}

// What a tile holds beyond a region does not change the region's list, where one list per view did.
TEST(ConsultedViewsTest, ARegionsListDoesNotDependOnTheNodesOutsideIt) {
  const SyntheticBlock block = ThreeViews();
  const auto views = block.SacViews();
  const ConsultedViews all = ConsultedViews::Select(views, GroundNodes(0, 20), OneViewPerRegion(10.0));
  const ConsultedViews east_only = ConsultedViews::Select(views, GroundNodes(10, 20), OneViewPerRegion(10.0));
  EXPECT_EQ(east_only.At(0, Ground(17, 5)), all.At(0, Ground(17, 5)));
  const ConsultedViews whole_all = ConsultedViews::Select(views, GroundNodes(0, 20), OneViewPerRegion(0.0));
  const ConsultedViews whole_east = ConsultedViews::Select(views, GroundNodes(10, 20), OneViewPerRegion(0.0));
  EXPECT_NE(whole_east.At(0, Ground(17, 5)), whole_all.At(0, Ground(17, 5)));
}

// A region of the view's range without nodes of it takes the list over all the view's nodes.
TEST(ConsultedViewsTest, ARegionWithoutNodesTakesTheWholeViewsList) {
  const SyntheticBlock block = ThreeViews();
  const auto views = block.SacViews();
  NodeTable nodes = GroundNodes(0, 20);
  // Keep the western half's south row and the eastern half's north row: regions (W, N) and (E, S) are empty.
  std::vector<SacNode> kept;
  for (const SacNode& node : nodes.nodes) {
    const bool west = node.point_in_world.x() < kEast + 10.0;
    const bool north = node.point_in_world.y() >= kNorth + 5.0;
    if (west != north) kept.push_back(node);
  }
  nodes.nodes = kept;
  ConsultOptions options = OneViewPerRegion(5.0);  // north rows [0, 5) and [5, 10) m
  options.max_views = 2;
  const ConsultedViews consulted = ConsultedViews::Select(views, nodes, options);
  EXPECT_EQ(consulted.At(0, Ground(3, 2)).front(), 1u);
  EXPECT_EQ(consulted.At(0, Ground(17, 7)).front(), 2u);
  options.region_m = 0.0;
  const ConsultedViews whole = ConsultedViews::Select(views, nodes, options);
  EXPECT_EQ(consulted.At(0, Ground(3, 7)), whole.At(0, Ground(3, 7)));
  EXPECT_EQ(whole.At(0, Ground(3, 7)).size(), 2u);
}

TEST(ConsultedViewsTest, PerViewListsAnswerEverywhere) {
  const ConsultedViews per_view({{1, 2}, {0}, {}});
  EXPECT_EQ(per_view.At(0, Ground(1e4, -1e4)), (std::vector<uint32_t>{1, 2}));
  EXPECT_EQ(per_view.At(1, Ground(0, 0)), (std::vector<uint32_t>{0}));
  EXPECT_TRUE(per_view.At(2, Ground(0, 0)).empty());
  EXPECT_EQ(per_view.max_list_size(), 2u);
  const ConsultedViews reversed = per_view.Sorted([](uint32_t a, uint32_t b) { return a > b; });
  EXPECT_EQ(reversed.At(0, Ground(0, 0)), (std::vector<uint32_t>{2, 1}));
}

}  // namespace
}  // namespace sacfuse
