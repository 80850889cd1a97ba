#include "jobs/open_input.h"

#include "core/error.h"
#include "io/colmap_workspace.h"
#include "io/openmvs_block.h"
#include "io/raster_block.h"

namespace sacfuse {

std::unique_ptr<DepthBlock> OpenInput(const InputOptions& input, const std::string& crs) {
  if (input.format == "colmap") {
    return std::make_unique<ColmapWorkspace>(
        input.path, input.depth_type == "photometric" ? ColmapDepthType::kPhotometric : ColmapDepthType::kGeometric);
  }
  if (input.format == "openmvs") return std::make_unique<OpenMvsBlock>(input.path);
  if (input.format == "rasters") {
    return std::make_unique<RasterBlock>(input.cameras.empty() ? FindCameraFile(input.path) : input.cameras,
                                         ParseDepthKind(input.depth_kind), crs);
  }
  throw ConfigError("input.format = " + input.format + ": unknown input format");
}

std::unique_ptr<DepthBlock> OpenNonEmptyInput(const InputOptions& input, const char* purpose, const std::string& crs) {
  std::unique_ptr<DepthBlock> block = OpenInput(input, crs);
  if (block->views().empty()) {
    throw InputError(input.path, std::string("the input has no views to ") + purpose);
  }
  return block;
}

}  // namespace sacfuse
