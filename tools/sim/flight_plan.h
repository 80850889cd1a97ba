#pragma once
// The airborne camera block: a Pentacam-like multi-camera (one nadir, four obliques tilted forward, backward,
// left and right) flown in lines along x (east) over the area. Per exposure all cameras share the centre.
//   nadir focal f_n = nadir_focal_mm / pixel_size_mm (pixels); flying height above ground H = gsd * f_n;
//   along-track baseline B = (1 - forward_overlap) * nadir_width_px * gsd;
//   line spacing L = (1 - side_overlap) * nadir_height_px * gsd;
// the grid of exposures is centred on the area and extended until no camera's footprint can reach the area;
// views whose ground footprint misses the area are dropped; max_nadir_views / max_oblique_views keep the views
// whose footprint centre is nearest the area centre.
// Camera axes: nadir x = east, y = south (image top = north). An oblique tilted by t toward horizontal unit h has
// z = sin(t) h - cos(t) up, y = -(cos(t) h + sin(t) up), x = y cross z (image top = far side).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/camera.h"
#include "core/rigid3.h"
#include "tools/sim/sim_options.h"
#include "tools/sim/surface.h"

namespace sacfuse::sim {

enum class ViewKind { kNadir, kObliqueForward, kObliqueBackward, kObliqueLeft, kObliqueRight };
// "nadir", "oblique_fwd", "oblique_bwd", "oblique_left", "oblique_right" (also the image sub-folder).
const char* ViewKindName(ViewKind kind);

struct PlannedView {
  std::string name;                // image name, e.g. "oblique_fwd/0007.jpg"
  ViewKind kind = ViewKind::kNadir;
  int exposure = 0;                // exposure number, shared by the cameras of one shot
  int line = 0;                    // flight line
  PinholeCamera camera;            // at image resolution
  Rigid3d cam_from_world;          // TRUE pose
  Eigen::Vector2d footprint_center = Eigen::Vector2d::Zero();  // ground footprint centroid (plane z = ground_z)
  double footprint_in_area_m2 = 0.0;                           // footprint area inside the scene area
};

struct FlightPlan {
  std::vector<PlannedView> views;  // flight order: exposure by exposure, nadir first
  double nadir_focal_px = 0.0;
  double oblique_focal_px = 0.0;
  double flying_height_m = 0.0;    // above ground_z
  double camera_z_m = 0.0;
  double baseline_m = 0.0;         // along-track distance between exposures
  double line_spacing_m = 0.0;
  int num_exposures = 0;           // exposures with at least one kept view
  int candidate_nadir = 0;         // views whose footprint meets the area, before the caps
  int candidate_oblique = 0;
  int num_nadir() const;
  int num_oblique() const;
};

FlightPlan PlanFlight(const SimOptions& options, const Box2d& area, double ground_z);

// World-from-camera rotation of a camera tilted by `tilt_rad` from nadir toward horizontal unit `toward`.
Eigen::Matrix3d WorldFromCameraRotation(const Eigen::Vector2d& toward, double tilt_rad);

// Ground footprint (image corners top-left, top-right, bottom-right, bottom-left) on the plane z = plane_z;
// false when a corner ray does not go down.
bool FootprintOnPlane(const PinholeCamera& camera, const Rigid3d& cam_from_world, double plane_z,
                      std::vector<Eigen::Vector2d>* corners);

// Area of a convex polygon clipped to a box (Sutherland-Hodgman + shoelace), m^2.
double ClippedArea(const std::vector<Eigen::Vector2d>& polygon, const Box2d& box);

}  // namespace sacfuse::sim
