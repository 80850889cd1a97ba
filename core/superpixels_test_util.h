#pragma once
// Test helpers shared by core/superpixels_test.cc and core/slic_fast_test.cc: synthetic images with known
// segments, and checks every superpixel map must pass (cluster statistics, connected clusters, label order).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/raster.h"
#include "core/superpixels.h"

namespace sacfuse::superpixels_test {


inline constexpr uint8_t kQuadrantColours[4][3] = {{200, 40, 40}, {40, 180, 60}, {50, 60, 210}, {220, 210, 50}};
inline constexpr float kQuadrantDepths[4] = {10.0f, 25.0f, 40.0f, 60.0f};

inline int Quadrant(int row, int col, int width, int height) { return (row >= height / 2 ? 2 : 0) + (col >= width / 2); }

// Four flat-coloured quadrants; depth is a tilted plane per quadrant, at different depths.
inline void MakeQuadrants(int width, int height, RgbImage* image, DepthMap* depth) {
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
inline void MakeTextured(int width, int height, uint64_t seed, RgbImage* image, DepthMap* depth) {
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
inline float Median(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : static_cast<float>(0.5 * (double(v[n / 2 - 1]) + v[n / 2]));
}

// Recomputes every cluster's statistics from the labels and checks them against the map.
inline void ExpectClusterStatsConsistent(const SuperpixelMap& map, const DepthMap& depth, int min_valid_pixels) {
  ASSERT_EQ(map.labels.width(), map.width);
  ASSERT_EQ(map.labels.height(), map.height);
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
inline void ExpectClustersConnected(const SuperpixelMap& map) {
  const std::vector<int32_t> labels = map.labels.ToVector();
  std::vector<char> seen(labels.size(), 0);
  std::vector<char> label_seen(map.clusters.size(), 0);
  std::vector<int> stack;
  for (int r = 0; r < map.height; ++r) {
    for (int c = 0; c < map.width; ++c) {
      const size_t start = static_cast<size_t>(r) * map.width + c;
      if (seen[start]) continue;
      const int32_t l = labels[start];
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
          if (!seen[j] && labels[j] == l) {
            seen[j] = 1;
            stack.push_back(static_cast<int>(j));
          }
        }
      }
    }
  }
}

// Inside the rectangle, labels first appear in increasing order starting at `first` (row-major scan).
inline void ExpectFirstAppearanceOrder(const SuperpixelMap& map, int row0, int row1, int col0, int col1, int32_t first) {
  int32_t next = first;
  for (int r = row0; r < row1; ++r) {
    for (int c = col0; c < col1; ++c) {
      const int32_t l = map.label(r, c);
      ASSERT_LE(l, next) << "row " << r << ", col " << c;
      if (l == next) ++next;
    }
  }
}

}  // namespace sacfuse::superpixels_test
