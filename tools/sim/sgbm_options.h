#pragma once
// Options of the matcher-made depth maps of `sacfuse simulate --depth sgbm` (tools/sim/sgbm_depth.h), apart from
// the code so that SimOptions can hold them without OpenCV's headers. Defaults: a two-view CPU pipeline's usual
// SGBM settings, as the independent aerial-bench and real-bench pipelines use them.
#include "tools/sim/stereo_sources.h"

namespace sacfuse::sim {

struct SgbmMatchOptions {
  int block_size = 5;         // matching block, pixels (odd); P1 = 8 b^2, P2 = p2_multiplier b^2
  int p2_multiplier = 32;
  int left_right_max_diff = 1;  // SGBM disp12MaxDiff, pixels
  int uniqueness_percent = 10;
  int speckle_window_px = 200;  // speckle filter: regions up to this many pixels ...
  int speckle_range = 2;        // ... whose disparities vary by more than this (x 16 internally) are removed
  int erode_px = 3;           // rim of the warped images left out
};

struct SgbmDepthOptions {
  StereoSourceOptions sources;
  SgbmMatchOptions match;
  double depth_percentile = 0.5;   // percent
  double depth_margin = 0.15;      // fraction of the depth
  double near_fraction = 0.65;     // fraction of the median sparse depth
  int max_disparities = 512;       // pixels
  double merge_tolerance = 0.01;   // pair depths agree within this fraction of their median
  int min_agree = 2;               // pairs that must agree to keep a pixel (1 = single-pair depths kept)
};

}  // namespace sacfuse::sim
