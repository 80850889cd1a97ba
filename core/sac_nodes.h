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
  uint32_t view = 0;      // index into the SacView vector
  uint32_t cluster = 0;
  bool valid = false;     // false when the cluster has no representative depth
};

struct NodeTable {
  std::vector<SacNode> nodes;
  std::vector<uint32_t> view_offset;  // size views + 1; node id of (v, c) = view_offset[v] + c

  uint32_t Id(uint32_t view, uint32_t cluster) const { return view_offset[view] + cluster; }
  size_t num_valid() const;
};

NodeTable BuildNodes(const std::vector<SacView>& views);

}  // namespace sacfuse
