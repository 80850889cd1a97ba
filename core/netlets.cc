#include "core/netlets.h"

#include <algorithm>
#include <numeric>

namespace sacfuse {

Netlets BuildNetlets(const NodeTable& nodes, const Correspondences& correspondences, double tau_m) {
  const size_t n = nodes.nodes.size();
  std::vector<uint32_t> order;
  order.reserve(n);
  for (uint32_t i = 0; i < n; ++i) {
    if (nodes.nodes[i].valid) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return correspondences.count(a) > correspondences.count(b);
  });

  Netlets out;
  out.member_offsets.push_back(0);
  out.edge_offsets.push_back(0);
  std::vector<uint8_t> taken(n, 0);
  std::vector<uint32_t> group;
  for (const uint32_t seed : order) {
    if (taken[seed]) continue;
    group.clear();
    group.push_back(seed);
    const Eigen::Vector3d& p_seed = nodes.nodes[seed].point_in_world;
    for (const uint32_t* it = correspondences.begin(seed); it != correspondences.end(seed); ++it) {
      const uint32_t c = *it;
      if (taken[c] || std::find(group.begin(), group.end(), c) != group.end()) continue;
      // One member per view keeps labels and members in one-to-one correspondence.
      bool same_view = false;
      for (uint32_t g : group) same_view = same_view || nodes.nodes[g].view == nodes.nodes[c].view;
      if (same_view) continue;
      if ((nodes.nodes[c].point_in_world - p_seed).norm() > tau_m) continue;
      group.push_back(c);
    }
    for (uint32_t g : group) taken[g] = 1;
    out.members.insert(out.members.end(), group.begin(), group.end());
    out.member_offsets.push_back(static_cast<uint32_t>(out.members.size()));
    for (size_t a = 0; a < group.size(); ++a) {
      for (size_t b = a + 1; b < group.size(); ++b) {
        const double d = (nodes.nodes[group[a]].point_in_world - nodes.nodes[group[b]].point_in_world).norm();
        if (d <= tau_m) out.edges.push_back({static_cast<uint16_t>(a), static_cast<uint16_t>(b), static_cast<float>(d)});
      }
    }
    out.edge_offsets.push_back(static_cast<uint32_t>(out.edges.size()));
  }
  return out;
}

}  // namespace sacfuse
