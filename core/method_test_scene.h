#pragma once
// Test-only helpers for the comparison methods' tests (header-only, used by core/*_test.cc): blocks of views
// with depth maps and no superpixels, and view plans given by hand. Scenes come from core/sac_test_scene.h.
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/method_views.h"
#include "core/raster.h"
#include "core/sac_test_scene.h"
#include "core/sac_view.h"

namespace sacfuse::testing {

// Nadir views of the per-pixel methods' tests: flying height, its GSD (f = 3000 px) and a shift between views of
// a whole number of pixels, so reprojected pixel centres land on pixel centres.
constexpr double kNadirHeightM = 500.0;
constexpr double kNadirGsdM = kNadirHeightM / 3000.0;
constexpr double kWholePixelShiftM = 48 * kNadirGsdM;  // 8 m

// Distinct ground cells of one GSD (origin at the scene's east/north corner) that the points fall in.
inline size_t UniqueGroundCells(const std::vector<FusedPoint>& points, double gsd_m) {
  std::set<std::pair<long, long>> cells;
  for (const FusedPoint& p : points) {
    cells.emplace(std::lround((p.point_in_world.x() - kEast) / gsd_m - 0.5),
                  std::lround((p.point_in_world.y() - kNorth) / gsd_m - 0.5));
  }
  return cells.size();
}

// Owns views and depth maps (no superpixels: the comparison methods do not read them).
struct MethodBlock {
  std::vector<View> views;
  std::vector<DepthMap> depths;
  std::vector<RgbImage> images;  // empty image = none
  void Add(const View& v, DepthMap d, RgbImage image = {}) {
    views.push_back(v);
    depths.push_back(std::move(d));
    images.push_back(std::move(image));
  }
  std::vector<SacView> SacViews() const {
    std::vector<SacView> out;
    for (size_t i = 0; i < views.size(); ++i) {
      out.push_back(MakeSacView(views[i], &depths[i], nullptr, images[i].empty() ? nullptr : &images[i]));
    }
    return out;
  }
};

// Every view a neighbour of every other (ascending), in the given processing order.
inline ViewPlan AllNeighbours(size_t n, std::vector<uint32_t> order) {
  ViewPlan plan;
  plan.neighbors.resize(n);
  for (uint32_t a = 0; a < n; ++a) {
    for (uint32_t b = 0; b < n; ++b) {
      if (a != b) plan.neighbors[a].push_back(b);
    }
  }
  plan.order = std::move(order);
  return plan;
}

// A uniform colour image of a depth map's size.
inline RgbImage UniformImage(const DepthMap& depth, uint8_t r, uint8_t g, uint8_t b) {
  RgbImage img(depth.width, depth.height, 3, 0);
  for (size_t i = 0; i < img.num_pixels(); ++i) {
    img.data[3 * i] = r;
    img.data[3 * i + 1] = g;
    img.data[3 * i + 2] = b;
  }
  return img;
}

// Exact z-depth of the tilted plane z = ground_z_m + slope * (x - x0_m) seen by a nadir view of
// core/sac_test_scene.h (camera z = down, so the depth is the ray parameter of unit-z rays).
inline DepthMap TiltedPlaneDepth(const View& view, double ground_z_m, double x0_m, double slope) {
  DepthMap depth(view.camera.width, view.camera.height, 1, 0.0f);
  const Rigid3d world_from_cam = view.cam_from_world.Inverse();
  const Eigen::Vector3d c = world_from_cam.translation;
  for (int r = 0; r < depth.height; ++r) {
    for (int col = 0; col < depth.width; ++col) {
      const Eigen::Vector3d ray = world_from_cam.rotation * view.camera.Unproject(col + 0.5, r + 0.5, 1.0);
      const double t = (ground_z_m - c.z() + slope * (c.x() - x0_m)) / (ray.z() - slope * ray.x());
      if (t > 0) depth.at(r, col) = static_cast<float>(t);
    }
  }
  return depth;
}

}  // namespace sacfuse::testing
