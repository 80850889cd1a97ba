#include "io/raster_block_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/photogrammetric_orientation.h"
#include "io/rgb_image_file.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

bool IsPlainRelativePath(const std::string& name) {
  const fs::path p(name);
  if (name.empty() || p.is_absolute() || name.find('\\') != std::string::npos) return false;
  for (const fs::path& part : p) {
    if (part == ".." || part == ".") return false;
  }
  return true;
}

// Depth along each pixel's ray from z (same formula as RasterBlock's inverse, on the raster's own camera).
void ZToRange(const PinholeCamera& cam, DepthMap* depth) {
  for (int r = 0; r < depth->height; ++r) {
    const double y = (r + 0.5 - cam.cy) / cam.fy;
    for (int c = 0; c < depth->width; ++c) {
      float& d = depth->at(r, c);
      if (!IsValidDepth(d)) continue;
      const double x = (c + 0.5 - cam.cx) / cam.fx;
      d = static_cast<float>(static_cast<double>(d) * std::sqrt(1.0 + x * x + y * y));
    }
  }
}

CameraFileView FileViewOf(const View& view, const RasterBlockWriteOptions& o) {
  CameraFileView fv;
  fv.image = view.name;
  fv.camera = view.camera;
  fv.geodetic = o.geodetic_positions;
  fv.attitude_frame = o.attitude_frame;
  const Eigen::Vector3d centre = view.CenterInWorld();
  const Eigen::Matrix3d rotation = PhotoCameraToWorldRotation(view.cam_from_world);
  const bool enu = o.attitude_frame == AttitudeFrame::kLocalEnu;
  if ((o.geodetic_positions || enu) && !o.crs.georeferenced()) {
    throw ConfigError(
        "crs = \"\": writing geodetic positions or local-ENU attitudes needs the project CRS of the "
        "input (set the config key crs)");
  }
  Eigen::Vector3d geo = Eigen::Vector3d::Zero();
  if (o.geodetic_positions) {
    geo = GeodeticFromProject(o.crs, centre);
  } else if (enu) {
    geo.head<2>() = LatLonFromProject(o.crs, centre);  // the attitude needs no height (nor a geoid grid)
  }
  fv.position = o.geodetic_positions ? geo : centre;
  fv.rotation =
      enu ? Eigen::Matrix3d(ProjectFromLocalEnuRotation(o.crs, geo.x(), geo.y()).transpose() * rotation) : rotation;
  return fv;
}

}  // namespace

std::string WriteRasterBlock(const DepthBlock& input, const std::string& out_dir, const RasterBlockWriteOptions& o) {
  CameraFile file;
  std::vector<CameraFileView>& file_views = file.views;
  for (const View& view : input.views()) {
    CameraFileView fv = FileViewOf(view, o);
    char fallback[32];
    std::snprintf(fallback, sizeof(fallback), "view%04u", view.index);
    const std::string stem = IsPlainRelativePath(view.name) ? view.name : std::string(fallback);
    fv.depth = "depth/" + stem + ".tif";
    DepthMap depth = input.ReadDepthMap(view);
    if (o.depth_kind == DepthKind::kRange) ZToRange(view.camera.Scaled(depth.width, depth.height), &depth);
    WriteTiffDepth((fs::path(out_dir) / fv.depth).string(), depth, o.tiff);
    const RgbImage image = input.ReadImage(view);
    if (!image.empty()) {
      fv.image_path = "images/" + stem + ".png";
      WriteRgbImagePng((fs::path(out_dir) / fv.image_path).string(), image);
    }
    file_views.push_back(std::move(fv));
  }
  const std::string camera_file = (fs::path(out_dir) / o.camera_file_name).string();
  const std::string ext = fs::path(o.camera_file_name).extension().string();
  if (o.scene_heights && (ext == ".yaml" || ext == ".yml")) file.scene_heights_m = input.SceneHeights();
  WriteCameraFile(camera_file, file, o.camera);
  return camera_file;
}

}  // namespace sacfuse
