#pragma once
// Writes any DepthBlock as a `rasters` input (io/raster_block.h): per view `depth/<name>.tif` (single-band float32
// TIFF) and `images/<name>.png` (the view's image re-encoded losslessly; omitted when the input has none), plus a
// camera file. How users hand a block to tools that read depth rasters + orientations, and how the tests check
// that every camera-file form fuses to the same points.
#include <string>

#include "io/crs.h"
#include "io/camera_file.h"
#include "io/depth_block.h"
#include "io/raster_block.h"
#include "io/tiff_depth.h"

namespace sacfuse {

struct RasterBlockWriteOptions {
  std::string camera_file_name = "cameras.yaml";        // in out_dir; .yaml/.yml or .csv
  CameraFileWriteOptions camera;                        // angles or matrix; interior in pixels or millimetres
  bool geodetic_positions = false;                      // lat_deg, lon_deg, h_m instead of x_m, y_m, z_m (needs crs)
  AttitudeFrame attitude_frame = AttitudeFrame::kGrid;  // local_enu needs crs
  Crs crs;                                              // the input's project CRS (config `crs`)
  DepthKind depth_kind = DepthKind::kZ;                 // range: distance along each pixel's ray
  TiffDepthWriteOptions tiff;                           // layout and compression of the depth rasters
  // YAML camera files: also write the input's SceneHeights() (e.g. COLMAP's sparse points) as scene_heights_m,
  // so tile planning gets the same height range as from the input (CSV files cannot hold them).
  bool scene_heights = true;
};

// Writes `input` into `out_dir` and returns the camera file's path. A view whose name is not a plain relative path
// (absolute, or with "..") is written as view%04u. Throws Error (ConfigError when geodetic positions or local ENU
// attitudes are asked for without a CRS), InputError when reading the input fails.
std::string WriteRasterBlock(const DepthBlock& input, const std::string& out_dir,
                             const RasterBlockWriteOptions& options);

}  // namespace sacfuse
