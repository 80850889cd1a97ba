// Our fast SLIC (core/slic_fast.h) through ComputeSuperpixels: flat halves kept apart, depth steps followed, labels
// connected, dense, ordered and the same for any thread count, fragments merged into the right neighbour.
#include "core/slic_fast.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "core/superpixels.h"
#include "core/superpixels_test_util.h"

namespace sacfuse {
namespace {

using namespace superpixels_test;  // NOLINT(build/namespaces): the shared helpers

TEST(SuperpixelsTest, FastKeepsTwoFlatHalvesApart) {
  const int width = 150, height = 90;
  for (int edge = 17; edge < 134; ++edge) {
    SCOPED_TRACE("edge at column " + std::to_string(edge));
    RgbImage image(width, height, 3);
    DepthMap depth(width, height, 1, 30.0f);
    for (int r = 0; r < height; ++r) {
      for (int c = 0; c < width; ++c) {
        const uint8_t left[3] = {90, 120, 60}, right[3] = {150, 110, 170};
        for (int k = 0; k < 3; ++k) image.at(r, c, k) = c < edge ? left[k] : right[k];
      }
    }
    SuperpixelOptions options;
    options.algorithm = "fast";
    for (const int iterations : {2, 4}) {
      options.iterations = iterations;
      const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
      std::vector<int> side(map.clusters.size(), -1);
      for (int r = 0; r < height; ++r) {
        for (int c = 0; c < width; ++c) {
          int& s = side[static_cast<size_t>(map.label(r, c))];
          if (s < 0) s = c < edge;
          ASSERT_EQ(s, c < edge ? 1 : 0) << "cluster " << map.label(r, c) << " straddles the edge at row " << r
                                         << ", col " << c << " (" << iterations << " iterations)";
        }
      }
      ExpectClustersConnected(map);
      ExpectClusterStatsConsistent(map, depth, options.min_valid_pixels);
    }
  }
}

// Identical colour everywhere, a depth step: only the weighted depth channel can separate the two sides.
TEST(SuperpixelsTest, FastFollowsADepthStepWithIdenticalColour) {
  const int width = 130, height = 70, step_col = 53;
  RgbImage image(width, height, 3, 128);
  DepthMap depth(width, height, 1);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) depth.at(r, c) = c < step_col ? 18.0f + 0.01f * r : 26.0f + 0.01f * r;
  }
  const auto straddling = [&](const SuperpixelMap& map) {
    std::vector<int> side(map.clusters.size(), -1);
    std::set<int32_t> bad;
    for (int r = 0; r < height; ++r) {
      for (int c = 0; c < width; ++c) {
        int& s = side[static_cast<size_t>(map.label(r, c))];
        if (s < 0) s = c < step_col;
        if (s != (c < step_col ? 1 : 0)) bad.insert(map.label(r, c));
      }
    }
    return bad.size();
  };
  SuperpixelOptions options;
  options.algorithm = "fast";
  EXPECT_GT(straddling(ComputeSuperpixels(image, depth, options)), 0u) << "colour alone cannot see the step";
  options.depth_weight = 10.0f;
  for (const int iterations : {2, 4}) {
    options.iterations = iterations;
    const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
    EXPECT_EQ(straddling(map), 0u) << iterations << " iterations";
    ExpectClustersConnected(map);
    ExpectClusterStatsConsistent(map, depth, options.min_valid_pixels);
  }
}

// Textured views of several shapes, block sizes, region sizes, iteration counts and depth weights (with invalid
// depths): labels in range, dense, one 4-connected region each, numbered in row-major block order / first
// appearance, no fragment below a quarter region except a block's first cluster, statistics equal to a brute-force
// recomputation, and identical for 1 and 2 threads.
TEST(SuperpixelsTest, FastLabelsAreConnectedDenseOrderedAndThreadCountInvariant) {
  struct Case {
    int width, height, block, region, iterations;
    float depth_weight;
  };
  for (const Case& k : std::vector<Case>{{160, 120, 64, 16, 4, 0.0f},
                                         {203, 157, 80, 16, 2, 5.0f},
                                         {97, 61, 1024, 7, 3, 0.0f},
                                         {64, 48, 32, 2, 1, 0.0f},
                                         {120, 90, 128, 24, 4, 20.0f}}) {
    SCOPED_TRACE(std::to_string(k.width) + "x" + std::to_string(k.height) + " block " + std::to_string(k.block) +
                 " region " + std::to_string(k.region));
    RgbImage image;
    DepthMap depth;
    MakeTextured(k.width, k.height, 17 + k.width, &image, &depth);
    for (int r = 0; r < k.height; ++r) {
      for (int c = 0; c < k.width; ++c) {
        if ((r * 13 + c * 7) % 11 == 0) depth.at(r, c) = 0.0f;
        if (r < 5 && c < 30) depth.at(r, c) = -1.0f;
      }
    }
    SuperpixelOptions options;
    options.algorithm = "fast";
    options.block_size_px = k.block;
    options.region_size_px = k.region;
    options.iterations = k.iterations;
    options.depth_weight = k.depth_weight;
    SuperpixelMap single;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      single = ComputeSuperpixels(image, depth, options);
    }
    SuperpixelMap parallel;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      parallel = ComputeSuperpixels(image, depth, options);
    }
    ASSERT_EQ(single.labels, parallel.labels);
    ASSERT_EQ(single.clusters.size(), parallel.clusters.size());
    for (size_t i = 0; i < single.clusters.size(); ++i) {
      EXPECT_EQ(single.clusters[i].depth_m, parallel.clusters[i].depth_m);
      EXPECT_EQ(single.clusters[i].centroid_col, parallel.clusters[i].centroid_col);
    }
    ExpectClusterStatsConsistent(single, depth, options.min_valid_pixels);
    ExpectClustersConnected(single);

    // Blocks as the driver cuts them (a trailing block narrower than 2 regions joins its neighbour).
    const auto edges = [&](int n) {
      std::vector<int> e{0};
      const int full = n / k.block;
      for (int i = 1; i <= full; ++i) e.push_back(i * k.block);
      if (full == 0) {
        e.push_back(n);
      } else if (n > e.back()) {
        if (n - e.back() < 2 * k.region) {
          e.back() = n;
        } else {
          e.push_back(n);
        }
      }
      return e;
    };
    const std::vector<int> xs = edges(k.width), ys = edges(k.height);
    int32_t first = 0;
    for (size_t by = 0; by + 1 < ys.size(); ++by) {
      for (size_t bx = 0; bx + 1 < xs.size(); ++bx) {
        ExpectFirstAppearanceOrder(single, ys[by], ys[by + 1], xs[bx], xs[bx + 1], first);
        std::set<int32_t> in_block;
        for (int r = ys[by]; r < ys[by + 1]; ++r) {
          for (int c = xs[bx]; c < xs[bx + 1]; ++c) in_block.insert(single.label(r, c));
        }
        ASSERT_EQ(*in_block.begin(), first);
        ASSERT_EQ(*in_block.rbegin(), first + static_cast<int32_t>(in_block.size()) - 1);
        // Fragments below 1/4 of the mean region were merged (the block's first cluster may be the exception).
        const int bw = xs[bx + 1] - xs[bx], bh = ys[by + 1] - ys[by];
        const int nx = std::max(1, (2 * bw + k.region) / (2 * k.region));
        const int ny = std::max(1, (2 * bh + k.region) / (2 * k.region));
        const double quarter = 0.25 * bw * bh / (nx * ny);
        for (const int32_t l : in_block) {
          if (l == first) continue;
          EXPECT_GE(single.clusters[static_cast<size_t>(l)].pixel_count, quarter) << "cluster " << l;
        }
        first += static_cast<int32_t>(in_block.size());
      }
    }
    EXPECT_EQ(static_cast<size_t>(first), single.clusters.size());
  }
}

// The connectivity pass on hand-made label rasters whose answer is known.
TEST(SuperpixelsTest, FastConnectivityMergesFragmentsIntoTheRightNeighbour) {
  const auto run = [](int width, int height, std::vector<int32_t> labels, double min_size, int* count) {
    std::vector<int32_t> out(labels.size(), -7);
    *count = FastSlicEnforceConnectivity(width, height, labels.data(), width, min_size, out.data(), width);
    return out;
  };
  int count = 0;
  // Label 5 appears twice, disconnected and large: two clusters. Numbering by first appearance.
  EXPECT_EQ(run(6, 3,
                {5, 5, 9, 9, 5, 5,  //
                 5, 5, 9, 9, 5, 5,  //
                 5, 5, 9, 9, 5, 5},
                4, &count),
            (std::vector<int32_t>{0, 0, 1, 1, 2, 2, 0, 0, 1, 1, 2, 2, 0, 0, 1, 1, 2, 2}));
  EXPECT_EQ(count, 3);
  // A 1-pixel fragment inside a row goes to the component left of it (the 3), one at column 0 to the component
  // above it (the 4); the two 3-pixel parts of label 1 stay separate clusters.
  EXPECT_EQ(run(5, 4,
                {1, 1, 2, 2, 2,  //
                 1, 3, 2, 2, 2,  //
                 4, 1, 2, 2, 2,  //
                 1, 1, 2, 2, 2},
                2, &count),
            (std::vector<int32_t>{0, 0, 1, 1, 1,  //
                                  0, 0, 1, 1, 1,  //
                                  0, 2, 1, 1, 1,  //
                                  2, 2, 1, 1, 1}));
  EXPECT_EQ(count, 3);
  // A small component at the top-left pixel joins the component right of it; numbering starts there.
  EXPECT_EQ(run(4, 3,
                {8, 2, 2, 3,  //
                 2, 2, 2, 3,  //
                 2, 2, 3, 3},
                3, &count),
            (std::vector<int32_t>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 1}));
  EXPECT_EQ(count, 2);
  // A small fragment merged into a small fragment ends in the large one before both.
  EXPECT_EQ(run(6, 2,
                {1, 1, 1, 2, 3, 1,  //
                 1, 1, 1, 1, 1, 1},
                3, &count),
            (std::vector<int32_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(count, 1);
  // min_size 0 keeps every component; in-place operation.
  std::vector<int32_t> labels{4, 7, 4, 4, 7, 4};
  EXPECT_EQ(FastSlicEnforceConnectivity(3, 2, labels.data(), 3, 0.0, labels.data(), 3), 3);
  EXPECT_EQ(labels, (std::vector<int32_t>{0, 1, 2, 0, 1, 2}));
}

// Not an assertion: prints the cost of the iteration count on a 2000x1500 textured image with 2 threads.

}  // namespace
}  // namespace sacfuse
