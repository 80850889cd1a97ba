// Netlet nodes: centroid back-projection and the rules that make a cluster invalid.
#include "core/sac_nodes.h"

#include <gtest/gtest.h>

#include "core/sac_test_scene.h"

namespace sacfuse {
namespace {

using testing::kEast;
using testing::kGroundZ;
using testing::kNorth;
using testing::NadirView;
using testing::PlaneDepth;

TEST(SacNodesTest, CentroidsBackProjectOntoThePlane) {
  const View view = NadirView(0, kEast, kNorth, 300.0);
  const DepthMap depth = PlaneDepth(view);
  const SuperpixelMap spx = testing::GridSuperpixels(depth, 6);
  const NodeTable table = BuildNodes({MakeSacView(view, &depth, &spx, nullptr)});
  ASSERT_EQ(table.nodes.size(), spx.clusters.size());
  EXPECT_EQ(table.num_valid(), spx.clusters.size());
  for (const SacNode& n : table.nodes) EXPECT_NEAR(n.point_in_world.z(), kGroundZ, 1e-3);
}

// A window of a larger raster keeps the full cluster table with centroids shifted into window coordinates;
// clusters whose centroid falls outside the window must not become nodes.
TEST(SacNodesTest, CentroidOutsideTheRasterIsInvalid) {
  const View view = NadirView(0, kEast, kNorth, 300.0);
  const DepthMap depth = PlaneDepth(view);
  SuperpixelMap spx = testing::GridSuperpixels(depth, 6);
  ASSERT_GE(spx.clusters.size(), 4u);
  spx.clusters[0].centroid_col = -0.5f;
  spx.clusters[1].centroid_row = -3.0f;
  spx.clusters[2].centroid_col = static_cast<float>(depth.width);
  spx.clusters[3].centroid_row = static_cast<float>(depth.height) + 2.0f;
  const NodeTable table = BuildNodes({MakeSacView(view, &depth, &spx, nullptr)});
  for (int c = 0; c < 4; ++c) EXPECT_FALSE(table.nodes[c].valid) << c;
  EXPECT_EQ(table.num_valid(), spx.clusters.size() - 4);
  EXPECT_TRUE(table.nodes[4].valid);
}

}  // namespace
}  // namespace sacfuse
