#include "core/superpixels.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/cluster_adjacency.h"
#include "core/error.h"
#include "core/slic_fast.h"
#include "core/superpixels_test_util.h"

namespace sacfuse {
namespace {

using namespace superpixels_test;  // NOLINT(build/namespaces): the shared helpers

TEST(SuperpixelsTest, QuadrantsAreNeverStraddled) {
  RgbImage image;
  DepthMap depth;
  MakeQuadrants(128, 96, &image, &depth);
  SuperpixelOptions options;
  for (const char* algorithm : {"slico", "slic", "mslic", "fast"}) {
    SCOPED_TRACE(algorithm);
    options.algorithm = algorithm;
    const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
    ASSERT_EQ(map.width, 128);
    ASSERT_EQ(map.height, 96);
    // Pixels outside their cluster's majority quadrant.
    std::vector<std::array<int, 4>> histogram(map.clusters.size(), std::array<int, 4>{});
    for (int r = 0; r < map.height; ++r) {
      for (int c = 0; c < map.width; ++c) ++histogram[map.label(r, c)][Quadrant(r, c, map.width, map.height)];
    }
    int stray = 0;
    for (const auto& h : histogram) stray += h[0] + h[1] + h[2] + h[3] - *std::max_element(h.begin(), h.end());
    if (std::string(algorithm) == "mslic") {
      // OpenCV's MSLIC merges fragments into a neighbour regardless of colour: a few pixels may stray.
      EXPECT_LT(stray, map.width * map.height / 100);
    } else {
      EXPECT_EQ(stray, 0) << "a cluster straddles a quadrant border";
    }
    const double expected = 128.0 * 96.0 / (16 * 16);
    // MSLIC merges similar neighbours, so flat quadrants end up with fewer, larger clusters.
    EXPECT_GE(map.clusters.size(), std::string(algorithm) == "mslic" ? 4.0 : 0.7 * expected);
    EXPECT_LE(map.clusters.size(), 1.3 * expected);
    ExpectClusterStatsConsistent(map, depth, options.min_valid_pixels);
  }
}

TEST(SuperpixelsTest, DepthWeightMakesClustersFollowDepthSteps) {
  const int width = 96, height = 64, step_col = 43;
  RgbImage image(width, height, 3, 128);
  DepthMap depth(width, height, 1);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) depth.at(r, c) = c < step_col ? 20.0f : 28.0f;
  }
  const auto straddling = [&](const SuperpixelMap& map) {
    std::vector<int> side(map.clusters.size(), -1);
    int bad = 0;
    std::set<int> bad_clusters;
    for (int r = 0; r < height; ++r) {
      for (int c = 0; c < width; ++c) {
        int& s = side[map.label(r, c)];
        const int here = c < step_col;
        if (s < 0) s = here;
        if (s != here) bad_clusters.insert(map.label(r, c));
      }
    }
    bad = static_cast<int>(bad_clusters.size());
    return bad;
  };
  SuperpixelOptions options;
  for (const char* algorithm : {"slico", "slic", "fast"}) {
    SCOPED_TRACE(algorithm);
    options.algorithm = algorithm;
    options.depth_weight = 0.0f;
    EXPECT_GT(straddling(ComputeSuperpixels(image, depth, options)), 0) << "colour alone cannot see the step";
    options.depth_weight = 10.0f;
    const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
    EXPECT_EQ(straddling(map), 0);
    ExpectClusterStatsConsistent(map, depth, options.min_valid_pixels);
  }
}

TEST(SuperpixelsTest, BlocksAreIndependentDenseAndThreadCountInvariant) {
  for (const char* algorithm : {"slico", "fast"}) {
  SCOPED_TRACE(algorithm);
  RgbImage image;
  DepthMap depth;
  MakeTextured(200, 150, 7, &image, &depth);
  SuperpixelOptions options;
  options.algorithm = algorithm;
  options.block_size_px = 64;
  // Blocks: columns [0,64) [64,128) [128,200) (the 8-pixel rest is merged), rows [0,64) [64,150).
  const auto block_of = [](int r, int c) { return (r < 64 ? 0 : 3) + std::min(c / 64, 2); };

  SuperpixelMap single;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    single = ComputeSuperpixels(image, depth, options);
  }
  const SuperpixelMap parallel = ComputeSuperpixels(image, depth, options);

  std::vector<int> block(single.clusters.size(), -1);
  std::vector<int32_t> block_min(6, std::numeric_limits<int32_t>::max()), block_max(6, -1);
  for (int r = 0; r < single.height; ++r) {
    for (int c = 0; c < single.width; ++c) {
      const int32_t l = single.label(r, c);
      ASSERT_GE(l, 0);
      ASSERT_LT(static_cast<size_t>(l), single.clusters.size());
      int& b = block[l];
      if (b < 0) b = block_of(r, c);
      ASSERT_EQ(b, block_of(r, c)) << "label " << l << " crosses a block border at row " << r << ", col " << c;
      block_min[b] = std::min(block_min[b], l);
      block_max[b] = std::max(block_max[b], l);
    }
  }
  for (int b = 1; b < 6; ++b) EXPECT_EQ(block_min[b], block_max[b - 1] + 1) << "row-major block numbering";
  EXPECT_EQ(block_min[0], 0);
  ExpectClusterStatsConsistent(single, depth, options.min_valid_pixels);

  ASSERT_EQ(parallel.labels, single.labels);
  ASSERT_EQ(parallel.clusters.size(), single.clusters.size());
  for (size_t i = 0; i < single.clusters.size(); ++i) {
    EXPECT_EQ(parallel.clusters[i].centroid_col, single.clusters[i].centroid_col);
    EXPECT_EQ(parallel.clusters[i].centroid_row, single.clusters[i].centroid_row);
    EXPECT_EQ(parallel.clusters[i].depth_m, single.clusters[i].depth_m);
    EXPECT_EQ(parallel.clusters[i].pixel_count, single.clusters[i].pixel_count);
  }
  }
}

TEST(SuperpixelsTest, OddSizesAndTinyImagesGetSaneLabels) {
  SuperpixelOptions options;
  options.block_size_px = 64;
  for (const char* algorithm : {"slico", "fast"}) {
    options.algorithm = algorithm;
    for (const auto& size : std::vector<std::pair<int, int>>{{100, 37}, {97, 131}, {10, 7}, {1, 1}, {20, 300}}) {
      SCOPED_TRACE(std::string(algorithm) + " " + std::to_string(size.first) + "x" + std::to_string(size.second));
      RgbImage image;
      DepthMap depth;
      MakeTextured(size.first, size.second, 3, &image, &depth);
      const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
      ASSERT_FALSE(map.clusters.empty());
      ExpectClusterStatsConsistent(map, depth, options.min_valid_pixels);
      if (options.algorithm == "fast") ExpectClustersConnected(map);
    }
  }
}

TEST(SuperpixelsTest, PixelsAlgorithmMakesOneClusterPerPixelWithItsDepth) {
  SuperpixelOptions options;
  options.algorithm = "pixels";
  options.block_size_px = 64;  // 100 x 37 -> blocks of 64 and 36 columns (the narrow one is merged: 100 wide)
  RgbImage image;
  DepthMap depth;
  MakeTextured(100, 37, 3, &image, &depth);
  depth.at(5, 7) = 0.0f;  // invalid
  const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
  ASSERT_EQ(map.clusters.size(), 100u * 37u);
  const std::vector<int32_t> all = map.labels.ToVector();
  std::set<int32_t> labels(all.begin(), all.end());
  EXPECT_EQ(labels.size(), map.clusters.size());
  for (int row = 0; row < 37; ++row) {
    for (int col = 0; col < 100; ++col) {
      const SuperpixelCluster& c = map.clusters[map.label(row, col)];
      EXPECT_EQ(c.pixel_count, 1u);
      EXPECT_FLOAT_EQ(c.centroid_col, col + 0.5f);
      EXPECT_FLOAT_EQ(c.centroid_row, row + 0.5f);
      EXPECT_EQ(c.depth_m, depth.at(row, col));  // 0 for the invalid pixel
    }
  }
  ExpectClusterStatsConsistent(map, depth, 1);
}

TEST(SuperpixelsTest, LargerImageIsResampledToTheDepthGrid) {
  RgbImage image;
  DepthMap depth;
  MakeQuadrants(128, 96, &image, &depth);
  RgbImage big(256, 192, 3);
  for (int r = 0; r < big.height; ++r) {
    for (int c = 0; c < big.width; ++c) {
      for (int k = 0; k < 3; ++k) big.at(r, c, k) = image.at(r / 2, c / 2, k);
    }
  }
  SuperpixelOptions options;
  for (const char* algorithm : {"slico", "fast"}) {
    SCOPED_TRACE(algorithm);
    options.algorithm = algorithm;
    const SuperpixelMap reference = ComputeSuperpixels(image, depth, options);
    const SuperpixelMap map = ComputeSuperpixels(big, depth, options);
    EXPECT_EQ(map.width, 128);
    EXPECT_EQ(map.height, 96);
    EXPECT_EQ(map.labels, reference.labels);  // flat 2x2 blocks area-average to the same colours
    ExpectClusterStatsConsistent(map, depth, options.min_valid_pixels);
  }

  RgbImage wrong_aspect(256, 128, 3);
  EXPECT_THROW(ComputeSuperpixels(wrong_aspect, depth, options), Error);
}

TEST(SuperpixelsTest, GreyImageEqualsReplicatedRgb) {
  RgbImage rgb;
  DepthMap depth;
  MakeTextured(90, 70, 13, &rgb, &depth);
  RgbImage grey(90, 70, 1);
  for (size_t i = 0; i < grey.num_pixels(); ++i) {
    grey.data[i] = rgb.data[3 * i + 1];
    rgb.data[3 * i] = rgb.data[3 * i + 2] = rgb.data[3 * i + 1];
  }
  SuperpixelOptions options;
  for (const char* algorithm : {"slico", "fast"}) {
    options.algorithm = algorithm;
    EXPECT_EQ(ComputeSuperpixels(grey, depth, options).labels, ComputeSuperpixels(rgb, depth, options).labels)
        << algorithm;
  }
}

TEST(SuperpixelsTest, InvalidDepthsAreIgnored) {
  RgbImage image;
  DepthMap depth;
  MakeQuadrants(128, 96, &image, &depth);
  for (int r = 0; r < 96; ++r) {
    for (int c = 0; c < 128; ++c) {
      const int q = Quadrant(r, c, 128, 96);
      if (q == 0) depth.at(r, c) = 0.0f;  // no depth at all
      if (q == 1 && (r + c) % 3 != 0) {
        depth.at(r, c) = (r % 2) ? -1.0f : std::numeric_limits<float>::quiet_NaN();
      }
      if (q == 3 && (r * 7 + c) % 5 == 0) depth.at(r, c) = std::numeric_limits<float>::infinity();
    }
  }
  SuperpixelOptions options;
  const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
  ExpectClusterStatsConsistent(map, depth, options.min_valid_pixels);
  int empty = 0;
  for (int r = 0; r < 48; ++r) {
    for (int c = 0; c < 64; ++c) {
      const SuperpixelCluster& cl = map.clusters[map.label(r, c)];
      EXPECT_EQ(cl.valid_count, 0u);
      EXPECT_EQ(cl.depth_m, 0.0f);
      ++empty;
    }
  }
  EXPECT_GT(empty, 0);
  for (const SuperpixelCluster& cl : map.clusters) {
    EXPECT_TRUE(std::isfinite(cl.depth_m));
    if (cl.valid_count > 0) {
      EXPECT_GT(cl.depth_m, 0.0f);
    }
  }

  options.min_valid_pixels = 1000;  // more than any cluster has
  for (const SuperpixelCluster& cl : ComputeSuperpixels(image, depth, options).clusters) {
    EXPECT_EQ(cl.depth_m, 0.0f);
  }
}

TEST(SuperpixelsTest, AdjacencyOfKnownLayout) {
  SuperpixelMap map;
  map.width = 5;
  map.height = 4;
  // 0 0 1 1 1
  // 0 0 1 1 1
  // 2 2 3 3 4
  // 2 2 3 3 4
  std::vector<int32_t> labels = {0, 0, 1, 1, 1, 0, 0, 1, 1, 1, 2, 2, 3, 3, 4, 2, 2, 3, 3, 4};
  map.labels = SuperpixelLabels(5, 4, labels);
  map.clusters.resize(5);
  const auto adjacency = ClusterAdjacency(map);
  const std::vector<std::vector<uint32_t>> expected = {{1, 2}, {0, 3, 4}, {0, 3}, {1, 2, 4}, {1, 3}};
  EXPECT_EQ(adjacency, expected);

  labels[0] = 7;
  map.labels = SuperpixelLabels(5, 4, labels);
  EXPECT_THROW(ClusterAdjacency(map), Error);
}

TEST(SuperpixelsTest, AdjacencyIsSymmetricOnRealSegmentation) {
  RgbImage image;
  DepthMap depth;
  MakeTextured(150, 100, 11, &image, &depth);
  SuperpixelOptions options;
  options.block_size_px = 64;
  const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
  const auto adjacency = ClusterAdjacency(map);
  ASSERT_EQ(adjacency.size(), map.clusters.size());
  std::set<std::pair<uint32_t, uint32_t>> truth;
  for (int r = 0; r < map.height; ++r) {
    for (int c = 0; c < map.width; ++c) {
      const auto a = static_cast<uint32_t>(map.label(r, c));
      if (c + 1 < map.width && map.label(r, c + 1) != map.label(r, c)) {
        truth.insert({a, static_cast<uint32_t>(map.label(r, c + 1))});
        truth.insert({static_cast<uint32_t>(map.label(r, c + 1)), a});
      }
      if (r + 1 < map.height && map.label(r + 1, c) != map.label(r, c)) {
        truth.insert({a, static_cast<uint32_t>(map.label(r + 1, c))});
        truth.insert({static_cast<uint32_t>(map.label(r + 1, c)), a});
      }
    }
  }
  std::set<std::pair<uint32_t, uint32_t>> got;
  for (uint32_t i = 0; i < adjacency.size(); ++i) {
    EXPECT_TRUE(std::is_sorted(adjacency[i].begin(), adjacency[i].end()));
    for (uint32_t j : adjacency[i]) got.insert({i, j});
  }
  EXPECT_EQ(got, truth);
}

TEST(SuperpixelsTest, ValidationNamesEveryBrokenField) {
  EXPECT_NO_THROW(ValidateSuperpixelOptions(SuperpixelOptions{}));
  SuperpixelOptions bad;
  bad.region_size_px = 1;
  bad.ruler = 0.0f;
  bad.iterations = 0;
  bad.algorithm = "seeds";
  bad.depth_weight = -1.0f;
  bad.min_valid_pixels = 0;
  try {
    ValidateSuperpixelOptions(bad);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    for (const char* part : {"SuperpixelOptions.region_size_px = 1", "SuperpixelOptions.ruler = 0",
                             "SuperpixelOptions.iterations = 0", "SuperpixelOptions.algorithm = seeds",
                             "SuperpixelOptions.depth_weight = -1", "SuperpixelOptions.min_valid_pixels = 0"}) {
      EXPECT_NE(m.find(part), std::string::npos) << part << " missing in: " << m;
    }
  }
  SuperpixelOptions small_block;
  small_block.block_size_px = 20;
  EXPECT_THROW(ValidateSuperpixelOptions(small_block), ConfigError);
  RgbImage image(8, 8, 3);
  DepthMap depth(8, 8, 1, 1.0f);
  EXPECT_THROW(ComputeSuperpixels(image, depth, small_block), ConfigError);
}

TEST(SuperpixelsTest, OptionsHashIsStableAndSensitive) {
  const SuperpixelOptions defaults;
  // Pinned: a change here silently invalidates every cached superpixel file; bump kAlgorithmVersion instead.
  EXPECT_EQ(SuperpixelOptionsHash(defaults), 0xd21e3213ce480556ull) << std::hex << SuperpixelOptionsHash(defaults);
  std::set<uint64_t> hashes{SuperpixelOptionsHash(defaults)};
  SuperpixelOptions o = defaults;
  o.region_size_px = 17;
  hashes.insert(SuperpixelOptionsHash(o));
  o = defaults;
  o.ruler = 11.0f;
  hashes.insert(SuperpixelOptionsHash(o));
  o = defaults;
  o.iterations = 5;
  hashes.insert(SuperpixelOptionsHash(o));
  o = defaults;
  o.algorithm = "slic";
  hashes.insert(SuperpixelOptionsHash(o));
  o = defaults;
  o.algorithm = "slico";
  hashes.insert(SuperpixelOptionsHash(o));
  o = defaults;
  o.block_size_px = 512;
  hashes.insert(SuperpixelOptionsHash(o));
  o = defaults;
  o.depth_weight = 1.0f;
  hashes.insert(SuperpixelOptionsHash(o));
  o = defaults;
  o.min_valid_pixels = 5;
  hashes.insert(SuperpixelOptionsHash(o));
  EXPECT_EQ(hashes.size(), 9u);
  o = defaults;
  o.depth_weight = -0.0f;
  EXPECT_EQ(SuperpixelOptionsHash(o), SuperpixelOptionsHash(defaults));
}

// --- algorithm "fast" (core/slic_fast.h).

// Two flat colours split at any column (on, beside and between seeds): no cluster may contain both. (One round
// alone is not enough: a pixel farther than S from every seed of its colour cannot be reached by one; the
// centres' first move fixes that.)
TEST(SuperpixelsTest, ThroughputReport) {
  RgbImage image;
  DepthMap depth;
  MakeTextured(2000, 1500, 5, &image, &depth);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  for (const auto& [algorithm, iterations] : std::vector<std::pair<std::string, int>>{
           {"slico", 10}, {"slico", 4}, {"slico", 2}, {"fast", 4}, {"fast", 2}}) {
    SuperpixelOptions options;
    options.algorithm = algorithm;
    options.iterations = iterations;
    const auto start = std::chrono::steady_clock::now();
    const SuperpixelMap map = ComputeSuperpixels(image, depth, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[ throughput ] %-5s, iterations %2d: %6.2f Mpx/s (%.3f s, %zu clusters, 2 threads)\n",
                algorithm.c_str(), iterations, image.num_pixels() / seconds / 1e6, seconds, map.clusters.size());
  }
}

}  // namespace
}  // namespace sacfuse
