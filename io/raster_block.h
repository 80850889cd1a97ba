#pragma once
// Generic photogrammetric input (`input.format: rasters`): a camera file (io/camera_file.h, YAML or CSV) with the
// interior and exterior orientation of every view, and per view a single-band float32 TIFF depth raster
// (io/tiff_depth.h) and optionally its image.
//
// - Views are numbered in camera-file order; a view's name is its `image` field.
// - Positions and attitudes become sacfuse poses in the project CRS (config `crs`) as io/camera_placement.h says
//   (input.cameras_crs, input.origin_m, geodetic positions, local-ENU attitudes), then
//   core/photogrammetric_orientation.h's CamFromWorldFromPhotogrammetric.
// - The intrinsics stay at image resolution; a depth raster may be smaller (the image size scaled by one factor,
//   each side rounded to within 1 px) and is back-projected through the camera scaled to it, as for COLMAP.
// - Depth: `z` (the coordinate along the optical axis, metres) or `range` (distance from the projection centre
//   along the ray through the pixel centre, metres), converted to z on read:
//   z = range / sqrt(1 + ((u - cx) / fx)^2 + ((v - cy) / fy)^2) at u = col + 0.5, v = row + 0.5 with the
//   camera scaled to the depth raster.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "io/camera_file.h"
#include "io/camera_placement.h"
#include "io/depth_block.h"

namespace sacfuse {

enum class DepthKind { kZ, kRange };

class RasterBlock : public DepthBlock {
 public:
  // Reads the camera file and turns every view into a sacfuse View (no depth raster is opened). `frame` holds the
  // config's crs, input.cameras_crs and input.origin_m (a crs text alone converts). Throws InputError naming the
  // camera file (line, view, field), ConfigError naming the key `crs` when views have geodetic positions or
  // local-ENU attitudes and `crs` is empty, or naming the CRS keys when they cannot be used.
  RasterBlock(const std::string& camera_file, DepthKind depth_kind, const CameraFrame& frame);

  const std::string& source() const override { return camera_file_; }
  const std::vector<View>& views() const override { return views_; }
  const std::vector<CameraFileView>& file_views() const { return file_.views; }

  std::string DepthMapPath(const View& view) const override;
  // The image file, or "" when the camera file gives none (ReadImage then returns an empty raster).
  std::string ImagePath(const View& view) const override;

  DepthRasterSize DepthSize(const View& view) const override;
  DepthMap ReadDepthMap(const View& view) const override;
  DepthMap ReadDepthWindow(const View& view, const PixelWindow& window) const override;
  RgbImage ReadImage(const View& view) const override;
  // The camera file's scene_heights_m (moved into the project CRS by CameraPlacement::HeightShiftM, averaged over
  // the views) when it has them; else z of back-projected depths sampled on a sparse grid
  // of every view (8 x 8 short row segments of 32 pixels: at most 64 strips or tiles decoded per view), computed
  // once.
  std::vector<double> SceneHeights() const override;
  std::string SceneHeightsSource() const override {
    return file_.scene_heights_m.empty() ? "depth-map sample" : "camera file scene_heights_m";
  }

 private:
  // Checks a raster's size against the view's image; returns the camera scaled to it.
  PinholeCamera DepthCamera(const View& view, int width, int height, const std::string& path) const;
  // Range -> z in place for a window whose top-left pixel is (row0, col0) of the raster.
  void RangeToZ(const PinholeCamera& depth_camera, int row0, int col0, DepthMap* depth) const;

  std::string camera_file_;
  std::string base_dir_;  // folder of the camera file: relative paths in it start here
  DepthKind depth_kind_;
  CameraFile file_;
  std::vector<View> views_;
  double scene_height_shift_m_ = 0.0;
  mutable std::once_flag heights_once_;
  mutable std::vector<double> heights_;
};

// The one cameras.yaml, cameras.yml or cameras.csv in `dir` (the default of input.cameras). Throws InputError
// naming `dir` when there is none or more than one.
std::string FindCameraFile(const std::string& dir);

DepthKind ParseDepthKind(const std::string& text);  // "z" | "range"; throws ConfigError naming input.depth_kind


}  // namespace sacfuse
