#pragma once
// Opens the input of a job (`input.format`, `input.path`, ...) as a DepthBlock. Every input format is dispatched
// here, so the rest of the job does not know which format it reads.
#include <memory>
#include <string>

#include "config/job_config.h"
#include "io/depth_block.h"

namespace sacfuse {

// Throws InputError for unreadable input (naming the file) and ConfigError for an unknown format. `crs` is the
// config's top-level `crs` (JobConfig::crs): formats with geodetic camera positions need it. The block's world is
// the project CRS: input.origin_m is added to every pose (io/reposed_block.h; camera files: io/camera_placement.h).
std::unique_ptr<DepthBlock> OpenInput(const InputOptions& input, const std::string& crs = "");

// As OpenInput, and throws InputError when the block has no views.
std::unique_ptr<DepthBlock> OpenNonEmptyInput(const InputOptions& input, const char* purpose,
                                              const std::string& crs = "");

}  // namespace sacfuse
