#pragma once
// Where the cross-section's points come from: LAS files streamed through the strip (the fused cloud, its tiles,
// the reference), and the depth maps back-projected into it (the "before fusion" points). Memory is bounded by
// the samples' capacities and, for depth maps, by one band of rows of one view's window at a time.
#include <cstdint>
#include <string>
#include <vector>

#include "io/depth_block.h"
#include "report/report_profile.h"

namespace sacfuse {

// Rows of a depth window read at once.
constexpr int kProfileDepthBandRows = 256;

// Streams every point of the LAS files and adds those inside the strip (any height) to `sample` (source ID as
// stored; `keep_source_id` false stores 0, e.g. for a reference). Throws InputError naming an unreadable file.
void SampleLasInStrip(const std::vector<std::string>& las_paths, const ProfileStrip& strip, ProfileSample* sample,
                      bool keep_source_id = true);

struct DepthStripStats {
  size_t views_read = 0;        // views whose depth window covers the strip
  uint64_t window_pixels = 0;   // depth pixels read
};

// The "before" points: every valid depth pixel of every view whose back-projection (through the pixel centre,
// core/backproject.h) falls inside the strip, with source ID view index + 1. Per view only the depth window that
// can see the strip's box at heights [strip.z_min_m, strip.z_max_m] is read (tiling/tile_windows.h, margin
// 1 px), in bands of kProfileDepthBandRows rows. Points outside that height range may be missed (they are
// outside the plot anyway). Throws InputError for an unreadable depth raster.
DepthStripStats SampleDepthInStrip(const DepthBlock& input, const ProfileStrip& strip, ProfileSample* sample);

}  // namespace sacfuse
