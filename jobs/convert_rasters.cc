#include "jobs/convert_rasters.h"

#include <limits>

#include "io/crs.h"
#include "core/error.h"
#include "io/raster_block_writer.h"

namespace sacfuse {

std::vector<std::string> RasterTargets() { return {"rasters", "rasters-csv", "rasters-geodetic"}; }

InputOptions ConvertToRasters(const DepthBlock& input, const std::string& target, const std::string& out_dir,
                              const std::string& crs) {
  RasterBlockWriteOptions o;
  o.tiff.nodata = std::numeric_limits<float>::quiet_NaN();
  try {
    o.crs = ParseProjectCrs(crs);
  } catch (const Error& e) {
    throw ConfigError(std::string("crs = \"") + crs + "\": " + e.what());
  }
  if (target == "rasters") {
    o.camera_file_name = "cameras.yaml";
  } else if (target == "rasters-csv") {
    o.camera_file_name = "cameras.csv";
    o.camera.rotation_matrix = true;
    o.camera.pixel_size_um = 1.0;
    o.depth_kind = DepthKind::kRange;
    o.tiff.tiled = false;
    o.tiff.rows_per_strip = 16;
    o.tiff.compression = TiffDepthWriteOptions::Compression::kLzw;
  } else if (target == "rasters-geodetic") {
    if (!o.crs.georeferenced()) {
      throw ConfigError(
          "crs = \"\": --to rasters-geodetic writes latitude/longitude, which needs the project CRS of "
          "the input: set the config key crs (e.g. crs: EPSG:25832)");
    }
    o.camera_file_name = "cameras.yaml";
    o.geodetic_positions = true;
    o.attitude_frame = AttitudeFrame::kLocalEnu;
  } else {
    throw ConfigError("--to " + target + ": not a rasters target");
  }
  InputOptions options;
  options.format = "rasters";
  options.path = out_dir;
  options.cameras = WriteRasterBlock(input, out_dir, o);
  options.depth_kind = o.depth_kind == DepthKind::kRange ? "range" : "z";
  return options;
}

}  // namespace sacfuse
