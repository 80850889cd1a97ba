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

#include "core/error.h"
#include "core/slic_fast.h"

namespace sacfuse {
namespace {

constexpr uint8_t kQuadrantColours[4][3] = {{200, 40, 40}, {40, 180, 60}, {50, 60, 210}, {220, 210, 50}};
constexpr float kQuadrantDepths[4] = {10.0f, 25.0f, 40.0f, 60.0f};

int Quadrant(int row, int col, int width, int height) { return (row >= height / 2 ? 2 : 0) + (col >= width / 2); }

// Four flat-coloured quadrants; depth is a tilted plane per quadrant, at different depths.
void MakeQuadrants(int width, int height, RgbImage* image, DepthMap* depth) {
  *image = RgbImage(width, height, 3);
  *depth = DepthMap(width, height, 1);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const int q = Quadrant(r, c, width, height);
      for (int k = 0; k < 3; ++k) image->at(r, c, k) = kQuadrantColours[q][k];
      depth->at(r, c) = kQuadrantDepths[q] + 0.01f * c + 0.02f * r;
    }
  }
}

// Smooth random colours (so SLIC has something to follow) with depth loosely tied to brightness.
void MakeTextured(int width, int height, uint64_t seed, RgbImage* image, DepthMap* depth) {
  cv::RNG rng(seed);
  cv::Mat small(std::max(1, height / 8), std::max(1, width / 8), CV_8UC3);
  rng.fill(small, cv::RNG::UNIFORM, 0, 256);
  cv::Mat big;
  cv::resize(small, big, cv::Size(width, height), 0, 0, cv::INTER_CUBIC);
  cv::Mat noise(height, width, CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 24);
  big += noise;
  *image = RgbImage(width, height, 3);
  *depth = DepthMap(width, height, 1);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const cv::Vec3b v = big.at<cv::Vec3b>(r, c);
      for (int k = 0; k < 3; ++k) image->at(r, c, k) = v[k];
      depth->at(r, c) = 100.0f + 0.05f * v[0] + 0.001f * c;
    }
  }
}

// Median convention of the implementation: mean of the two middle values for even counts.
float Median(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : static_cast<float>(0.5 * (double(v[n / 2 - 1]) + v[n / 2]));
}

// Recomputes every cluster's statistics from the labels and checks them against the map.
void ExpectClusterStatsConsistent(const SuperpixelMap& map, const DepthMap& depth, int min_valid_pixels) {
  ASSERT_EQ(map.labels.size(), static_cast<size_t>(map.width) * map.height);
  const size_t n = map.clusters.size();
  std::vector<double> sc(n, 0), sr(n, 0);
  std::vector<uint32_t> count(n, 0);
  std::vector<std::vector<float>> depths(n);
  for (int r = 0; r < map.height; ++r) {
    for (int c = 0; c < map.width; ++c) {
      const int32_t l = map.label(r, c);
      ASSERT_GE(l, 0);
      ASSERT_LT(static_cast<size_t>(l), n);
      sc[l] += c + 0.5;
      sr[l] += r + 0.5;
      ++count[l];
      if (IsValidDepth(depth.at(r, c))) depths[l].push_back(depth.at(r, c));
    }
  }
  for (size_t i = 0; i < n; ++i) {
    const SuperpixelCluster& cl = map.clusters[i];
    ASSERT_GT(count[i], 0u) << "label " << i << " unused (labels not dense)";
    EXPECT_EQ(cl.pixel_count, count[i]) << i;
    EXPECT_EQ(cl.valid_count, depths[i].size()) << i;
    EXPECT_NEAR(cl.centroid_col, sc[i] / count[i], 1e-3) << i;
    EXPECT_NEAR(cl.centroid_row, sr[i] / count[i], 1e-3) << i;
    const float expected =
        static_cast<int>(depths[i].size()) >= min_valid_pixels ? Median(depths[i]) : 0.0f;
    EXPECT_FLOAT_EQ(cl.depth_m, expected) << i;
  }
}

// Every label is one 4-connected region (BFS over the raster, brute force).
void ExpectClustersConnected(const SuperpixelMap& map) {
  std::vector<char> seen(map.labels.size(), 0);
  std::vector<char> label_seen(map.clusters.size(), 0);
  std::vector<int> stack;
  for (int r = 0; r < map.height; ++r) {
    for (int c = 0; c < map.width; ++c) {
      const size_t start = static_cast<size_t>(r) * map.width + c;
      if (seen[start]) continue;
      const int32_t l = map.labels[start];
      ASSERT_FALSE(label_seen[static_cast<size_t>(l)]) << "label " << l << " has a second component at row " << r
                                                       << ", col " << c;
      label_seen[static_cast<size_t>(l)] = 1;
      seen[start] = 1;
      stack.assign(1, static_cast<int>(start));
      while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        const int rr = i / map.width, cc = i % map.width;
        const int nr[4] = {rr - 1, rr + 1, rr, rr};
        const int nc[4] = {cc, cc, cc - 1, cc + 1};
        for (int k = 0; k < 4; ++k) {
          if (nr[k] < 0 || nc[k] < 0 || nr[k] >= map.height || nc[k] >= map.width) continue;
          const size_t j = static_cast<size_t>(nr[k]) * map.width + nc[k];
          if (!seen[j] && map.labels[j] == l) {
            seen[j] = 1;
            stack.push_back(static_cast<int>(j));
          }
        }
      }
    }
  }
}

// Inside the rectangle, labels first appear in increasing order starting at `first` (row-major scan).
void ExpectFirstAppearanceOrder(const SuperpixelMap& map, int row0, int row1, int col0, int col1, int32_t first) {
  int32_t next = first;
  for (int r = row0; r < row1; ++r) {
    for (int c = col0; c < col1; ++c) {
      const int32_t l = map.label(r, c);
      ASSERT_LE(l, next) << "row " << r << ", col " << c;
      if (l == next) ++next;
    }
  }
}

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
  std::set<int32_t> labels(map.labels.begin(), map.labels.end());
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
  map.labels = {0, 0, 1, 1, 1, 0, 0, 1, 1, 1, 2, 2, 3, 3, 4, 2, 2, 3, 3, 4};
  map.clusters.resize(5);
  const auto adjacency = ClusterAdjacency(map);
  const std::vector<std::vector<uint32_t>> expected = {{1, 2}, {0, 3, 4}, {0, 3}, {1, 2, 4}, {1, 3}};
  EXPECT_EQ(adjacency, expected);

  map.labels[0] = 7;
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
