#pragma once
// Opens the input of a job (`input.format`, `input.path`, ...) as a DepthBlock. Every input format is dispatched
// here, so the rest of the job does not know which format it reads.
#include <memory>

#include "config/job_config.h"
#include "io/depth_block.h"

namespace sacfuse {

// Throws InputError for unreadable input (naming the file) and ConfigError for an unknown format.
std::unique_ptr<DepthBlock> OpenInput(const InputOptions& input);

// As OpenInput, and throws InputError when the block has no views.
std::unique_ptr<DepthBlock> OpenNonEmptyInput(const InputOptions& input, const char* purpose);

}  // namespace sacfuse
