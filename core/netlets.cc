#include "core/netlets.h"

#include <algorithm>

namespace sacfuse {

Netlets BuildNetlets(const NodeTable& nodes, const Correspondences& correspondences, double tau_m,
                     size_t max_members) {
  const size_t n = nodes.nodes.size();
  constexpr uint32_t kFree = UINT32_MAX;
  std::vector<uint32_t> order;
  order.reserve(n);
  for (uint32_t i = 0; i < n; ++i) {
    if (nodes.nodes[i].valid) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return correspondences.count(a) > correspondences.count(b);
  });
  auto within_tau = [&](uint32_t a, uint32_t b) {
    return (nodes.nodes[a].point_in_world - nodes.nodes[b].point_in_world).norm() <= tau_m;
  };

  // Phase 1: seeds with their free correspondents, one per view.
  std::vector<uint32_t> netlet_of(n, kFree);
  std::vector<std::vector<uint32_t>> groups;
  std::vector<uint32_t> leftovers;
  for (const uint32_t seed : order) {
    if (netlet_of[seed] != kFree) continue;
    std::vector<uint32_t> group = {seed};
    for (const uint32_t* it = correspondences.begin(seed); it != correspondences.end(seed); ++it) {
      const uint32_t c = *it;
      if (netlet_of[c] != kFree || !within_tau(seed, c)) continue;
      bool same_view = false;
      for (uint32_t g : group) same_view = same_view || nodes.nodes[g].view == nodes.nodes[c].view;
      if (same_view || std::find(group.begin(), group.end(), c) != group.end()) continue;
      group.push_back(c);
    }
    if (group.size() == 1) {
      leftovers.push_back(seed);  // decided in phase 2
      netlet_of[seed] = kFree - 1;
      continue;
    }
    for (uint32_t g : group) netlet_of[g] = static_cast<uint32_t>(groups.size());
    groups.push_back(std::move(group));
  }
  // Phase 2: a lone node joins the Netlet of its first correspondent within tau that has room.
  std::sort(leftovers.begin(), leftovers.end());
  for (const uint32_t node : leftovers) {
    uint32_t target = kFree;
    for (const uint32_t* it = correspondences.begin(node); it != correspondences.end(node); ++it) {
      const uint32_t t = netlet_of[*it];
      if (t < groups.size() && groups[t].size() < max_members && within_tau(node, *it)) {
        target = t;
        break;
      }
    }
    if (target == kFree) {
      target = static_cast<uint32_t>(groups.size());
      groups.push_back({});
    }
    groups[target].push_back(node);
    netlet_of[node] = target;
  }

  return NetletsFromGroups(nodes, groups, tau_m);
}

Netlets BuildNodeNetlets(const NodeTable& nodes, const Correspondences& correspondences, double tau_m) {
  std::vector<std::vector<uint32_t>> groups;
  for (uint32_t i = 0; i < nodes.nodes.size(); ++i) {
    if (!nodes.nodes[i].valid) continue;
    groups.push_back(NodeNetletMembers(nodes, i, correspondences.begin(i), correspondences.end(i), tau_m));
  }
  return NetletsFromGroups(nodes, groups, tau_m);
}

std::vector<uint32_t> NodeNetletMembers(const NodeTable& nodes, uint32_t node, const uint32_t* first,
                                        const uint32_t* last, double tau_m) {
  std::vector<uint32_t> group = {node};
  for (const uint32_t* it = first; it != last; ++it) {
    if ((nodes.nodes[*it].point_in_world - nodes.nodes[node].point_in_world).norm() <= tau_m) group.push_back(*it);
  }
  return group;
}

Netlets NetletsFromGroups(const NodeTable& nodes, const std::vector<std::vector<uint32_t>>& groups, double tau_m) {
  Netlets out;
  out.member_offsets.push_back(0);
  out.edge_offsets.push_back(0);
  for (const auto& group : groups) {
    out.members.insert(out.members.end(), group.begin(), group.end());
    out.member_offsets.push_back(static_cast<uint32_t>(out.members.size()));
    for (size_t a = 0; a < group.size(); ++a) {
      for (size_t b = a + 1; b < group.size(); ++b) {
        const double d = (nodes.nodes[group[a]].point_in_world - nodes.nodes[group[b]].point_in_world).norm();
        if (d <= tau_m) {
          out.edges.push_back({static_cast<uint16_t>(a), static_cast<uint16_t>(b), static_cast<float>(d)});
        }
      }
    }
    out.edge_offsets.push_back(static_cast<uint32_t>(out.edges.size()));
  }
  return out;
}

}  // namespace sacfuse
