#include "jobs/open_input.h"

#include "core/error.h"
#include "io/colmap_workspace.h"

namespace sacfuse {

std::unique_ptr<DepthBlock> OpenInput(const InputOptions& input) {
  if (input.format == "colmap") {
    return std::make_unique<ColmapWorkspace>(
        input.path, input.depth_type == "photometric" ? ColmapDepthType::kPhotometric : ColmapDepthType::kGeometric);
  }
  throw ConfigError("input.format = " + input.format + ": unknown input format");
}

std::unique_ptr<DepthBlock> OpenNonEmptyInput(const InputOptions& input, const char* purpose) {
  std::unique_ptr<DepthBlock> block = OpenInput(input);
  if (block->views().empty()) {
    throw InputError(input.path, std::string("the input has no views to ") + purpose);
  }
  return block;
}

}  // namespace sacfuse
