#pragma once
// Test-only helpers (header-only, used by core/*_test.cc): nadir cameras over a horizontal plane at UTM-sized
// coordinates, exact depth maps, and regular grid "superpixels", so SAC tests have answers known by construction.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/point.h"
#include "core/sac_view.h"
#include "core/superpixels.h"

namespace sacfuse::testing {

constexpr double kEast = 390000.0;     // scene origin, metres (UTM 32N-sized)
constexpr double kNorth = 5705000.0;
constexpr double kGroundZ = 100.0;

// A nadir camera (looking straight down, image x = east, image y = south) centred above (east, north).
inline View NadirView(uint32_t index, double east, double north, double height_above_ground, int width = 120,
                      int height = 90, double focal_px = 3000.0) {
  View v;
  v.index = index;
  v.name = "nadir/" + std::to_string(index) + ".png";
  v.camera = {width, height, focal_px, focal_px, width / 2.0, height / 2.0};
  // Camera axes in world: x = east, y = south, z = down.
  Eigen::Matrix3d world_from_cam_rot;
  world_from_cam_rot << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  const Eigen::Vector3d center(east, north, kGroundZ + height_above_ground);
  Rigid3d world_from_cam{Eigen::Quaterniond(world_from_cam_rot), center};
  v.cam_from_world = world_from_cam.Inverse();
  return v;
}

// Exact z-depth of the plane z = kGroundZ (+ bias_m added to every depth), invalid outside [x_min, x_max] east.
inline DepthMap PlaneDepth(const View& view, double bias_m = 0.0, double x_min = -1e300, double x_max = 1e300) {
  DepthMap depth(view.camera.width, view.camera.height, 1, 0.0f);
  const Rigid3d world_from_cam = view.cam_from_world.Inverse();
  for (int r = 0; r < depth.height; ++r) {
    for (int c = 0; c < depth.width; ++c) {
      const Eigen::Vector3d ray = world_from_cam.rotation * view.camera.Unproject(c + 0.5, r + 0.5, 1.0);
      const double t = (kGroundZ - world_from_cam.translation.z()) / ray.z();  // z-depth == t for unit-z rays
      const Eigen::Vector3d hit = world_from_cam.translation + t * ray;
      if (hit.x() < x_min || hit.x() > x_max) continue;
      depth.at(r, c) = static_cast<float>(t + bias_m);
    }
  }
  return depth;
}

// Regular square cells of `cell` pixels as superpixels, with centroids and median depths.
inline SuperpixelMap GridSuperpixels(const DepthMap& depth, int cell) {
  SuperpixelMap map;
  map.width = depth.width;
  map.height = depth.height;
  const int cols = (depth.width + cell - 1) / cell;
  const int rows = (depth.height + cell - 1) / cell;
  std::vector<int32_t> labels(static_cast<size_t>(depth.width) * depth.height);
  map.clusters.resize(static_cast<size_t>(cols) * rows);
  std::vector<std::vector<float>> depths(map.clusters.size());
  for (int r = 0; r < depth.height; ++r) {
    for (int c = 0; c < depth.width; ++c) {
      const int label = (r / cell) * cols + c / cell;
      labels[static_cast<size_t>(r) * depth.width + c] = label;
      auto& cl = map.clusters[label];
      cl.centroid_col += c + 0.5f;
      cl.centroid_row += r + 0.5f;
      ++cl.pixel_count;
      if (IsValidDepth(depth.at(r, c))) depths[label].push_back(depth.at(r, c));
    }
  }
  for (size_t i = 0; i < map.clusters.size(); ++i) {
    auto& cl = map.clusters[i];
    cl.centroid_col /= cl.pixel_count;
    cl.centroid_row /= cl.pixel_count;
    cl.valid_count = static_cast<uint32_t>(depths[i].size());
    if (!depths[i].empty()) {
      std::sort(depths[i].begin(), depths[i].end());
      cl.depth_m = depths[i][depths[i].size() / 2];
    }
  }
  map.labels = SuperpixelLabels(map.width, map.height, labels);
  return map;
}

// Owns the rasters of a small synthetic block and hands out SacViews.
struct SyntheticBlock {
  std::vector<View> views;
  std::vector<DepthMap> depths;
  std::vector<SuperpixelMap> superpixels;

  void Add(const View& view, const DepthMap& depth, int cell = 6) {
    views.push_back(view);
    depths.push_back(depth);
    superpixels.push_back(GridSuperpixels(depth, cell));
  }
  std::vector<SacView> SacViews() const {
    std::vector<SacView> out;
    for (size_t i = 0; i < views.size(); ++i) out.push_back(MakeSacView(views[i], &depths[i], &superpixels[i], nullptr));
    return out;
  }
};

// Independent Gaussian noise of sigma_m metres added to every depth of `depth`.
inline void AddDepthNoise(DepthMap* depth, double sigma_m, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, sigma_m);
  for (float& z : depth->data) z += static_cast<float>(noise(*rng));
}

// Collects points written to a sink.
class CollectingSink : public PointSink {
 public:
  void Write(const FusedPoint* points, size_t count) override { points_.insert(points_.end(), points, points + count); }
  const std::vector<FusedPoint>& points() const { return points_; }

 private:
  std::vector<FusedPoint> points_;
};

}  // namespace sacfuse::testing
