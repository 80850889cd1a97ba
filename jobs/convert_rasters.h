#pragma once
// The `rasters` targets of `sacfuse convert` (io/raster_block_writer.h): one per camera-file form, so every
// reading path can be exercised from one block.
//   rasters           cameras.yaml: interior in pixels, x_m/y_m/z_m, omega/phi/kappa w.r.t. the grid; depth z;
//                     tiled (256 px) Deflate TIFFs
//   rasters-csv       cameras.csv: interior in millimetres on a nominal 1 um pixel pitch (focal_mm = focal_px /
//                     1000), x_m/y_m/z_m, r11..r33 w.r.t. the grid; depth as range along the ray; striped
//                     (16 rows) LZW TIFFs
//   rasters-geodetic  cameras.yaml: lat_deg/lon_deg/h_m, omega/phi/kappa w.r.t. local ENU at each camera (needs
//                     the config's crs); depth z; tiled Deflate TIFFs
// Invalid depth pixels are written as NaN with GDAL_NODATA "nan".
#include <string>
#include <vector>

#include "config/job_config.h"
#include "io/depth_block.h"

namespace sacfuse {

std::vector<std::string> RasterTargets();

// Writes `input` as `target` (one of RasterTargets()) into `out_dir`; returns the input options reading it back.
// `crs` is the input's project CRS (config `crs`); rasters-geodetic throws ConfigError naming `crs` without it.
InputOptions ConvertToRasters(const DepthBlock& input, const std::string& target, const std::string& out_dir,
                              const std::string& crs);

}  // namespace sacfuse
