#pragma once
// Netlet nodes: one per superpixel cluster of each view, at the cluster centroid back-projected with the
// cluster's robust (median) depth (Algorithm 1: GetCentroids, Get3DPoint). Node id = view offset + cluster index.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/sac_view.h"

namespace sacfuse {

struct SacNode {
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();
  float depth_m = 0.0f;   // in its own view
  float gsd_m = 0.0f;     // its view's local GSD at that depth
  float sigma_rel = 0.0f; // relative stereo depth uncertainty, depth^2 / focal (sigma_z = z^2 sigma_d / (f B) at
                          // equal baselines B); only ratios between views are used
  Eigen::Vector3f normal_in_world = Eigen::Vector3f::Zero();  // plane fit of the cluster's pixels, facing the camera
  Eigen::Vector3f ray_in_world = Eigen::Vector3f::Zero();     // unit direction from the camera centre to the point
  uint32_t view = 0;      // index into the SacView vector
  uint32_t cluster = 0;
  bool valid = false;     // false when the cluster has no representative depth or its centroid is off the raster
};

struct NodeTable {
  std::vector<SacNode> nodes;
  std::vector<uint32_t> view_offset;  // size views + 1; node id of (v, c) = view_offset[v] + c

  uint32_t Id(uint32_t view, uint32_t cluster) const { return view_offset[view] + cluster; }
  size_t num_valid() const;
};

// Also fits a plane to each cluster's back-projected pixels for its normal (least squares; clusters with fewer than
// 3 valid pixels face their camera).
NodeTable BuildNodes(const std::vector<SacView>& views);

}  // namespace sacfuse
