#include "core/sac_nodes.h"

#include <array>

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include "core/backproject.h"
#include "core/error.h"

namespace sacfuse {
namespace {

// Per cluster: sums of camera-frame points and their outer products (relative to the cluster's first pixel, so the
// covariance is computed without cancellation), for plane-fit normals.
struct PlaneAccumulator {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();
  uint32_t count = 0;
  void Add(const Eigen::Vector3d& p) {
    if (count == 0) origin = p;
    const Eigen::Vector3d q = p - origin;
    sum += q;
    sum_outer += q * q.transpose();
    ++count;
  }
  // Unit normal in the camera frame facing the camera (toward -point), or nullopt-like zero when undetermined.
  Eigen::Vector3d Normal() const {
    if (count < 3) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d mean = sum / count;
    const Eigen::Matrix3d cov = sum_outer / count - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(cov);
    Eigen::Vector3d n = solver.eigenvectors().col(0);
    if (n.dot(origin + mean) > 0) n = -n;
    return n.normalized();
  }
};

// Plane-fit normals of every cluster of a view, in the camera frame (every second pixel in each direction).
std::vector<Eigen::Vector3d> ClusterNormalsInCamera(const SacView& view) {
  std::vector<PlaneAccumulator> acc(view.superpixels->clusters.size());
  const DepthMap& depth = *view.depth;
  for (int row = 0; row < depth.height; row += 2) {
    for (int col = 0; col < depth.width; col += 2) {
      const float d = depth.at(row, col);
      if (!IsValidDepth(d)) continue;
      acc[view.superpixels->label(row, col)].Add(DepthPixelInCamera(view.depth_camera, col, row, d));
    }
  }
  std::vector<Eigen::Vector3d> normals(acc.size());
  for (size_t c = 0; c < acc.size(); ++c) normals[c] = acc[c].Normal();
  return normals;
}

}  // namespace

size_t NodeTable::num_valid() const {
  size_t n = 0;
  for (const auto& node : nodes) n += node.valid ? 1 : 0;
  return n;
}

NodeTable BuildNodes(const std::vector<SacView>& views) {
  NodeTable table;
  table.view_offset.resize(views.size() + 1, 0);
  for (size_t v = 0; v < views.size(); ++v) {
    const SuperpixelMap* spx = views[v].superpixels;
    if (spx == nullptr || spx->width != views[v].depth->width || spx->height != views[v].depth->height) {
      throw Error("view " + views[v].view.name + ": superpixel raster missing or not the depth map's size");
    }
    table.view_offset[v + 1] = table.view_offset[v] + static_cast<uint32_t>(spx->clusters.size());
  }
  table.nodes.resize(table.view_offset.back());
  tbb::parallel_for(size_t{0}, views.size(), [&](size_t v) {
    const SacView& view = views[v];
    const auto& clusters = view.superpixels->clusters;
    const std::vector<Eigen::Vector3d> normals = ClusterNormalsInCamera(view);
    const Eigen::Vector3d center = view.world_from_cam.translation;
    for (size_t c = 0; c < clusters.size(); ++c) {
      SacNode& node = table.nodes[table.view_offset[v] + c];
      node.view = static_cast<uint32_t>(v);
      node.cluster = static_cast<uint32_t>(c);
      const float d = clusters[c].depth_m;
      if (!IsValidDepth(d)) continue;
      // A centroid outside the raster (a window of a larger depth map: the cluster lies mostly outside it) does
      // not become a node; its pixels in the window are the window's margin.
      const float ccol = clusters[c].centroid_col, crow = clusters[c].centroid_row;
      if (!(ccol >= 0.0f && crow >= 0.0f && ccol < view.depth->width && crow < view.depth->height)) continue;
      node.valid = true;
      node.depth_m = d;
      node.gsd_m = static_cast<float>(view.GsdAt(d));
      node.sigma_rel = static_cast<float>(static_cast<double>(d) * d / view.depth_camera.fx);
      const Eigen::Vector3d point_in_cam =
          view.depth_camera.Unproject(clusters[c].centroid_col, clusters[c].centroid_row, d);
      node.point_in_world = view.world_from_cam * point_in_cam;
      node.ray_in_world = (node.point_in_world - center).normalized().cast<float>();
      const Eigen::Vector3d n_cam = normals[c].squaredNorm() > 0 ? normals[c] : Eigen::Vector3d(-point_in_cam.normalized());
      node.normal_in_world = (view.world_from_cam.rotation * n_cam).cast<float>();
    }
  });
  return table;
}

}  // namespace sacfuse
