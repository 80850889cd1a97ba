#pragma once
// Merge of one view's pair depths (one depth map per stereo pair, on the view's grid) into its depth map, as a
// two-view pipeline's filter does: per pixel, the median of the valid pair depths; the pairs within
// `relative_tolerance` of it agree; the pixel keeps the median of the agreeing depths where at least `min_agree`
// pairs agree (min_agree 1 keeps single-pair depths: more of the matcher's errors), else it is invalid.
// Medians of an even count are the mean of the two middle values.
#include <cstdint>
#include <vector>

#include "core/raster.h"

namespace sacfuse::sim {

struct PairMerge {
  DepthMap depth;                // 0 = invalid
  std::vector<uint8_t> agreeing; // per pixel (row-major), how many pairs agreed (0 where none was valid)
};

// All `pair_depths` must have one size; an empty list gives an empty result. Throws std::invalid_argument otherwise.
PairMerge MergePairDepths(const std::vector<DepthMap>& pair_depths, double relative_tolerance, int min_agree);

}  // namespace sacfuse::sim
