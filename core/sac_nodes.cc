#include "core/sac_nodes.h"

#include <tbb/parallel_for.h>

#include "core/error.h"

namespace sacfuse {

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
    for (size_t c = 0; c < clusters.size(); ++c) {
      SacNode& node = table.nodes[table.view_offset[v] + c];
      node.view = static_cast<uint32_t>(v);
      node.cluster = static_cast<uint32_t>(c);
      const float d = clusters[c].depth_m;
      if (!IsValidDepth(d)) continue;
      node.valid = true;
      node.depth_m = d;
      node.gsd_m = static_cast<float>(view.GsdAt(d));
      node.point_in_world =
          view.world_from_cam * view.depth_camera.Unproject(clusters[c].centroid_col, clusters[c].centroid_row, d);
    }
  });
  return table;
}

}  // namespace sacfuse
