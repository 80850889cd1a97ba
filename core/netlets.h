#pragma once
// Markov Netlets (Algorithm 1): small networks over a node and its corresponding nodes. Nodes are the MRF
// variables; the candidate labels of a Netlet are the views of its members (label k = "take member k's view");
// edges join members closer than tau with weight exp(-distance) (Eq. 3).
//
// The paper builds one point group per node, so groups overlap and a node would be labelled many times. We
// partition instead, deterministically:
//  1. seeds are visited by most correspondences first, then node id; a Netlet takes the seed plus those of its
//     correspondents (one per view) that no earlier Netlet took and that lie within tau;
//  2. a node left alone joins the Netlet of its first correspondent within tau (Netlets then hold several nodes
//     of one view), up to max_members, so that it can still collapse instead of staying a singleton.
// Every valid node belongs to exactly one Netlet, so labels are unambiguous and Netlets solve independently.
// The candidate labels of a Netlet are the distinct views of its members.
#include <cstdint>
#include <vector>

#include "core/correspondences.h"
#include "core/sac_nodes.h"

namespace sacfuse {

struct NetletEdge {
  uint16_t i = 0, j = 0;  // member positions
  float distance_m = 0.0f;
};

struct Netlets {
  std::vector<uint32_t> member_offsets;  // netlets + 1 (CSR over members)
  std::vector<uint32_t> members;         // node ids; the seed first
  std::vector<uint32_t> edge_offsets;    // netlets + 1 (CSR over edges)
  std::vector<NetletEdge> edges;

  size_t size() const { return member_offsets.empty() ? 0 : member_offsets.size() - 1; }
  size_t num_members(size_t n) const { return member_offsets[n + 1] - member_offsets[n]; }
  const uint32_t* members_of(size_t n) const { return members.data() + member_offsets[n]; }
};

Netlets BuildNetlets(const NodeTable& nodes, const Correspondences& correspondences, double tau_m,
                     size_t max_members = 24);

// The paper's own construction (Algorithm 1): one Netlet per valid node, made of the node (member 0) and its
// correspondents within tau. Netlets overlap; each decides only its centre's label.
Netlets BuildNodeNetlets(const NodeTable& nodes, const Correspondences& correspondences, double tau_m);

// The members of a per-node Netlet: `node`, then those of its correspondents [first, last) within tau.
std::vector<uint32_t> NodeNetletMembers(const NodeTable& nodes, uint32_t node, const uint32_t* first,
                                        const uint32_t* last, double tau_m);

// Netlets of the given member lists (the first member of each is its seed), with their edges (members within tau).
Netlets NetletsFromGroups(const NodeTable& nodes, const std::vector<std::vector<uint32_t>>& groups, double tau_m);

}  // namespace sacfuse
