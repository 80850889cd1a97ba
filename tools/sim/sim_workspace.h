#pragma once
// File helpers of the simulated workspace: folders, JPEG images, relative symlinks.
#include <string>

#include "core/raster.h"

namespace sacfuse::sim {

// Creates the parent folders of `path`.
void CreateParentDirs(const std::string& path);
// RGB raster -> JPEG at `quality`, written atomically. Throws Error on failure.
void WriteJpeg(const std::string& path, const RgbImage& image, int quality);
// A symlink at `link_path` pointing to `target_path` by a path relative to the link's folder (replaces an
// existing link). Throws Error on failure.
void CreateRelativeSymlink(const std::string& target_path, const std::string& link_path);

}  // namespace sacfuse::sim
