#include "jobs/open_input.h"

#include "core/error.h"
#include "io/colmap_workspace.h"
#include "io/openmvs_block.h"
#include "io/raster_block.h"
#include "io/reposed_block.h"

namespace sacfuse {

namespace {

Eigen::Vector3d Origin(const InputOptions& input) {
  if (input.origin_m.size() != 3) {
    throw ConfigError("input.origin_m: " + std::to_string(input.origin_m.size()) +
                      " numbers; must be [east, north, height] in metres");
  }
  return {input.origin_m[0], input.origin_m[1], input.origin_m[2]};
}

}  // namespace

std::unique_ptr<DepthBlock> OpenInput(const InputOptions& input, const std::string& crs) {
  const Eigen::Vector3d origin = Origin(input);
  if (input.format == "colmap") {
    return WithWorldOrigin(
        std::make_unique<ColmapWorkspace>(input.path, input.depth_type == "photometric" ? ColmapDepthType::kPhotometric
                                                                                         : ColmapDepthType::kGeometric),
        origin);
  }
  if (input.format == "openmvs") return WithWorldOrigin(std::make_unique<OpenMvsBlock>(input.path), origin);
  if (input.format == "rasters") {
    // The camera file's positions may be in another CRS: the origin applies before their transformation.
    return std::make_unique<RasterBlock>(input.cameras.empty() ? FindCameraFile(input.path) : input.cameras,
                                         ParseDepthKind(input.depth_kind), CameraFrame(crs, input.cameras_crs, origin));
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
