#pragma once
// Which superpixel clusters of a view touch: the neighbourhood of SAC's smoothness term between adjacent clusters
// (core/sac_labeling.h).
#include <cstdint>
#include <vector>

#include "core/superpixels.h"

namespace sacfuse {

// Neighbouring clusters (4-connectivity): result[i] lists the clusters sharing an edge with cluster i, sorted,
// without duplicates (symmetric: j in result[i] <=> i in result[j]). result.size() == map.clusters.size(). Throws
// Error when the labels do not match the map's size or a label is out of range.
std::vector<std::vector<uint32_t>> ClusterAdjacency(const SuperpixelMap& map);

}  // namespace sacfuse
