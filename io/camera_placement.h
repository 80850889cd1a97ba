#pragma once
// How the positions and attitudes of a camera file (io/camera_file.h) become sacfuse poses in the project CRS:
// - x_m, y_m, z_m are in input.cameras_crs (default: the project CRS `crs`), offset by input.origin_m (a workspace
//   in a local frame shifted to a round origin: the CRS coordinates are file + origin, exactly in doubles);
// - lat_deg, lon_deg, h_m (ellipsoidal) are on the datum of that CRS's geodetic CRS; input.origin_m does not apply
//   to them (a view with them and a non-zero origin is an error);
// - positions are transformed into the project CRS through PROJ (io/crs_transform.h: datum shifts, geoid grids);
// - attitudes w.r.t. local east-north-up are turned by ProjectFromLocalEnuRotation at the camera (grid
//   convergence); attitudes w.r.t. the grid of another projected input.cameras_crs are turned by the difference
//   of the two CRSs' rotations at the camera.
#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/rigid3.h"
#include "io/camera_file.h"
#include "io/crs.h"

namespace sacfuse {

class CrsTransform;

// Where a camera file's coordinates are: the config keys crs, input.cameras_crs and input.origin_m.
struct CameraFrame {
  CameraFrame(std::string crs_text = "", std::string cameras_crs_text = "",
              const Eigen::Vector3d& origin = Eigen::Vector3d::Zero())
      : crs(std::move(crs_text)), cameras_crs(std::move(cameras_crs_text)), origin_m(origin) {}
  CameraFrame(const char* crs_text) : CameraFrame(std::string(crs_text)) {}  // a crs text alone
  std::string crs;
  std::string cameras_crs;
  Eigen::Vector3d origin_m;
};

class CameraPlacement {
 public:
  // Throws ConfigError naming the key (crs, input.cameras_crs) when a CRS is not accepted, when input.cameras_crs
  // is set without crs, or when PROJ has no transformation between them (e.g. a missing geoid grid).
  explicit CameraPlacement(const CameraFrame& frame);
  ~CameraPlacement();

  // The view's pose in the project CRS. Throws ConfigError (naming `crs`) when the view needs a CRS and there is
  // none, InputError(file) naming the view when its position cannot be placed.
  Rigid3d CamFromWorld(const CameraFileView& view, const std::string& file) const;
  // Project-CRS height minus camera-file height of a view placed by CamFromWorld: input.origin_m's z, plus with
  // input.cameras_crs the vertical change of the transformation at the view (e.g. a geoid height).
  double HeightShiftM(const CameraFileView& view, const Rigid3d& cam_from_world) const;

  const Crs& project_crs() const { return project_; }

 private:
  Crs project_;
  Crs cameras_;  // kNone: positions in the project CRS
  Eigen::Vector3d origin_m_;
  std::unique_ptr<CrsTransform> positions_;  // cameras_ -> project_ (with cameras_crs)
  std::unique_ptr<CrsTransform> geodetic_;   // geodetic CRS of cameras_ -> project_ (with cameras_crs)
};

}  // namespace sacfuse
