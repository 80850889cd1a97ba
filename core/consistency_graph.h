#pragma once
// Dense-matching consistency of one depth map: for each pixel, the views whose depth maps the matcher found
// consistent with it (COLMAP's stereo/consistency_graphs/*.bin). Stored sparsely as CSR over pixels.
#include <cstdint>
#include <vector>

namespace sacfuse {

struct ConsistencyGraph {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> pixel_offsets;  // width*height + 1 offsets into view_indices (CSR)
  std::vector<uint32_t> view_indices;   // block view indices (0-based)

  bool empty() const { return pixel_offsets.empty(); }
  // Views consistent at pixel (row, col): [begin, end) into view_indices.
  std::pair<const uint32_t*, const uint32_t*> At(int row, int col) const {
    const size_t p = static_cast<size_t>(row) * width + col;
    return {view_indices.data() + pixel_offsets[p], view_indices.data() + pixel_offsets[p + 1]};
  }
};

}  // namespace sacfuse
