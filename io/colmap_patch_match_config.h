#pragma once
// stereo/patch-match.cfg of a COLMAP dense workspace: which source images each reference image was matched with.
// COLMAP's format (image_undistorter writes it, patch_match_stereo reads it): lines alternate between a reference
// image name and its sources, which are either image names separated by commas, or "__all__", or "__auto__, N"
// (PatchMatch picks N sources itself). A pipeline that matches pairs (SGBM on rectified pairs, real-bench,
// `sacfuse simulate --depth sgbm`) lists each view's partners by name.
//
// What fusion takes from it: the views whose depth maps come from the same image pairs (View::matching_partners).
// A pair's two depth maps share the pair's matching errors, so one agreeing with the other is weak evidence
// (core/point_verdicts.h, fusion.independent_support).
#include <cstdint>
#include <string>
#include <vector>

#include "core/view.h"

namespace sacfuse {

struct PatchMatchEntry {
  std::string image;                  // the reference image
  std::vector<std::string> sources;   // named sources (empty when automatic)
  bool automatic = false;             // "__all__" or "__auto__, N": the sources are not named
  int line = 0;                       // line of the reference image name (1-based)
};

// Reads the file. Empty lines and surrounding whitespace are ignored, as COLMAP does. Throws InputError naming the
// file and line: a reference image without a sources line, an empty source name, a reference listed twice, an image
// listed among its own sources, an "__auto__" line whose count is not a positive integer.
std::vector<PatchMatchEntry> ReadPatchMatchConfig(const std::string& path);

// The matching partners of each view of `views` (by position; views[i].index == i), both directions: b is a
// partner of a when a lists b among its sources or b lists a. Names of the config that are not among the views
// (images left out of the fusion) are ignored. Empty lists for every view when any entry of a view is automatic
// (the sources are unknown). Each list is sorted.
std::vector<std::vector<uint32_t>> MatchingPartners(const std::vector<PatchMatchEntry>& entries,
                                                    const std::vector<View>& views);

}  // namespace sacfuse
