#pragma once
// Camera files: the interior and exterior orientation of every view of a block plus the paths of its depth raster
// and (optionally) its image, in YAML or CSV (the file's extension decides: .yaml/.yml or .csv). Both forms use the
// same field names; docs/inputs.md has a worked example of each.
//
// Fields of a view (units in the names):
//   image          image name: names the view (unique); LAS point source ID = position in the file + 1
//   depth          depth raster (single-band float32 TIFF), relative to the camera file's folder
//   image_path     optional image file (any format OpenCV decodes), relative to the camera file's folder; without
//                  it the view has no colours
//   width_px, height_px                 image size, pixels
//   interior orientation, one of
//     focal_px (or fx_px + fy_px), cx_px, cy_px
//                  pixels, in sacfuse's pixel frame: (0, 0) is the top-left CORNER of the top-left pixel, u right,
//                  v down (cx_px, cy_px default to the image centre width_px / 2, height_px / 2)
//     focal_mm, pixel_size_um, ppx_mm, ppy_mm
//                  millimetres with a square pixel pitch in micrometres; the principal point offset (ppx, ppy) is
//                  measured from the image CENTRE in the photogrammetric image frame (x right, y UP), so
//                  cx_px = width_px / 2 + ppx_mm / pitch_mm and cy_px = height_px / 2 - ppy_mm / pitch_mm
//                  (ppx_mm, ppy_mm default to 0)
//   position, one of
//     x_m, y_m, z_m              projection centre in the project CRS (config key `crs`), metres, or in
//                                input.cameras_crs, offset by input.origin_m (io/camera_placement.h)
//     lat_deg, lon_deg, h_m      geodetic latitude/longitude (degrees, on the CRS's datum) and ellipsoidal
//                                height (metres); needs the config key `crs`
//   attitude, one of
//     omega_deg, phi_deg, kappa_deg   R = R_x(omega) R_y(phi) R_z(kappa) (core/photogrammetric_orientation.h)
//     r11 .. r33 (row-major)          R itself
//                  R maps the photogrammetric camera frame (x right, y up, z toward the viewer; looks along -z)
//                  INTO the attitude frame (image to object)
//   attitude_frame grid: the project CRS's axes (x east/grid east, y grid north, z up)
//                  local_enu: east-north-up at the camera's position (true north; as GNSS/IMU systems give
//                  it); turned into the project frame with io/crs.h's ProjectFromLocalEnuRotation (needs `crs`)
//                  Default: local_enu for geodetic positions, grid for project positions.
//
// YAML: a top-level map with `views:` (a list of maps of the fields above), optional `cameras:` (a map from an id
// to interior fields; a view names its interior with `camera: id`, and its own fields override), optional
// `attitude_frame:` (the default for every view), optional `scene_heights_m:` (see CameraFile), optional
// `version: 1`. In YAML the attitude matrix may also be given as `rotation: [[r11, r12, r13], [r21, r22, r23],
// [r31, r32, r33]]`.
// CSV: comma-separated; the first non-comment line names the columns (any order, the field names above, no
// `camera`); one view per following line; an empty cell is an absent field; '#' starts a comment line; cells may
// be double-quoted ("" inside is a quote).
//
// Unknown fields, missing or mixed forms, duplicate image names, non-numbers and non-rotation matrices throw
// InputError naming the file, line, view and field.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/camera.h"

namespace sacfuse {

enum class AttitudeFrame { kGrid, kLocalEnu };

struct CameraFileView {
  std::string image;       // image name (the view's name)
  std::string depth;       // depth raster path as written in the file
  std::string image_path;  // image path as written in the file; "" = none
  PinholeCamera camera;    // at image resolution, sacfuse pixel convention
  bool geodetic = false;   // position is (lat_deg, lon_deg, h_m) instead of (x_m, y_m, z_m)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // photogrammetric camera -> attitude frame
  AttitudeFrame attitude_frame = AttitudeFrame::kGrid;
  int line = 0;  // line of the view in the file (messages); 0 when built in code
};

struct CameraFile {
  std::vector<CameraFileView> views;
  // YAML only (`scene_heights_m: [z, ...]`, metres in the project CRS): heights of known scene points such as tie
  // points. They only bound the height range of tile planning (DepthBlock::SceneHeights); without them the depth
  // rasters are sampled instead. Empty when absent.
  std::vector<double> scene_heights_m;
};

// Reads a camera file (format from the extension). Throws InputError naming the file.
CameraFile ReadCameraFile(const std::string& path);

// A view as messages name it: "line 12: view \"nadir/0005.jpg\"" ("view ..." alone when built in code).
std::string CameraFileViewText(const CameraFileView& view);

struct CameraFileWriteOptions {
  bool rotation_matrix = false;  // write r11..r33 (else omega_deg, phi_deg, kappa_deg)
  // Write the interior in millimetres with this pixel pitch (micrometres); 0 = in pixels. Views with fx != fy are
  // always written in pixels.
  double pixel_size_um = 0.0;
};

// Writes atomically as YAML or CSV (from the extension); YAML groups equal interiors under `cameras`. Numbers are
// written with 17 significant digits, so reading gives back the same doubles (angles to ~1e-15 deg). Throws Error
// for another extension, scene heights for a CSV file, or a write failure.
void WriteCameraFile(const std::string& path, const CameraFile& file, const CameraFileWriteOptions& options = {});

}  // namespace sacfuse
