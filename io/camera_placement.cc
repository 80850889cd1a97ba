#include "io/camera_placement.h"

#include "core/error.h"
#include "core/photogrammetric_orientation.h"
#include "io/crs_transform.h"

namespace sacfuse {
namespace {

std::string Quoted(const std::string& s) { return "\"" + s + "\""; }

template <typename F>
Crs ParseAsConfig(F&& parse) {
  try {
    return parse();
  } catch (const ConfigError&) {
    throw;
  } catch (const Error& e) {
    throw ConfigError(e.what());
  }
}

}  // namespace

CameraPlacement::CameraPlacement(const CameraFrame& frame)
    : project_(ParseAsConfig([&] { return ParseProjectCrs(frame.crs); })),
      cameras_(ParseAsConfig([&] { return ParseInputCrs(frame.cameras_crs); })),
      origin_m_(frame.origin_m) {
  if (!cameras_.georeferenced()) return;
  if (!project_.georeferenced()) {
    throw ConfigError("input.cameras_crs = " + Quoted(frame.cameras_crs) +
                      ": positions in another CRS need the project CRS to transform them into: set the config key "
                      "crs");
  }
  try {
    if (cameras_.kind() != Crs::Kind::kGeographic) positions_ = std::make_unique<CrsTransform>(cameras_, project_);
    geodetic_ = std::make_unique<CrsTransform>(GeodeticCrsOf(cameras_), project_);
  } catch (const Error& e) {
    throw ConfigError("input.cameras_crs = " + Quoted(frame.cameras_crs) + " -> crs = " + Quoted(frame.crs) + ": " +
                      e.what());
  }
}

CameraPlacement::~CameraPlacement() = default;

Rigid3d CameraPlacement::CamFromWorld(const CameraFileView& v, const std::string& file) const {
  const bool enu = v.attitude_frame == AttitudeFrame::kLocalEnu;
  if ((v.geodetic || enu) && !project_.georeferenced()) {
    throw ConfigError(std::string("crs = \"\": ") + file + ": " + CameraFileViewText(v) + " gives " +
                      (v.geodetic ? "a geodetic position (lat_deg, lon_deg, h_m)"
                                  : "its attitude w.r.t. local east-north-up (attitude_frame: local_enu)") +
                      ", which needs the project CRS: set the config key crs (e.g. crs: EPSG:25832)");
  }
  const bool other_crs = cameras_.georeferenced();
  const Crs& frame_crs = other_crs ? cameras_ : project_;
  try {
    if (v.geodetic && !origin_m_.isZero()) {
      throw Error("input.origin_m applies to x_m, y_m, z_m; this view gives lat_deg, lon_deg, h_m");
    }
    if (!v.geodetic && other_crs && cameras_.kind() == Crs::Kind::kGeographic) {
      throw Error("input.cameras_crs " + Quoted(cameras_.text()) + " is geographic: give lat_deg, lon_deg, h_m");
    }
    Eigen::Vector3d centre;
    Eigen::Vector2d lat_lon = Eigen::Vector2d::Zero();
    if (v.geodetic) {
      lat_lon = v.position.head<2>();
      if (other_crs) CheckAreaOfUse(project_, lat_lon.x(), lat_lon.y());
      centre = other_crs ? geodetic_->Apply(v.position)
                         : ProjectFromGeodetic(project_, v.position.x(), v.position.y(), v.position.z());
    } else {
      const Eigen::Vector3d in_frame = v.position + origin_m_;
      centre = other_crs ? positions_->Apply(in_frame) : in_frame;
      if (enu || other_crs) lat_lon = LatLonFromProject(frame_crs, in_frame);
    }
    Eigen::Matrix3d rotation = v.rotation;
    if (enu) {
      rotation = ProjectFromLocalEnuRotation(project_, lat_lon.x(), lat_lon.y()) * v.rotation;
    } else if (other_crs) {
      if (cameras_.kind() == Crs::Kind::kGeographic) {
        throw Error("attitude_frame grid refers to the axes of input.cameras_crs, and the geographic " +
                    Quoted(cameras_.text()) + " has none: give the attitude w.r.t. local east-north-up "
                    "(attitude_frame: local_enu)");
      }
      rotation = ProjectFromLocalEnuRotation(project_, lat_lon.x(), lat_lon.y()) *
                 ProjectFromLocalEnuRotation(cameras_, lat_lon.x(), lat_lon.y()).transpose() * v.rotation;
    }
    return CamFromWorldFromPhotogrammetric(rotation, centre);
  } catch (const ConfigError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(file,
                     CameraFileViewText(v) + ": cannot place the camera in crs " + project_.text() + ": " + e.what());
  }
}

double CameraPlacement::HeightShiftM(const CameraFileView& v, const Rigid3d& cam_from_world) const {
  if (!cameras_.georeferenced()) return origin_m_.z();
  return cam_from_world.Inverse().translation.z() - v.position.z();
}

}  // namespace sacfuse
