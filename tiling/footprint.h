#pragma once
// Ground footprints of views: where a camera's image rectangle meets a horizontal plane. Used to find the project
// area, the views that see a place, and (later) the views a tile needs.
#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/box2d.h"
#include "core/view.h"

namespace sacfuse {


// World XY of the four image corners (top-left, top-right, bottom-right, bottom-left) projected onto the plane
// z = ground_z_m. Empty when a corner ray does not hit the plane in front of the camera (e.g. above horizon).
std::optional<std::array<Eigen::Vector2d, 4>> GroundFootprint(const View& view, double ground_z_m);

// Axis-aligned bounds of the footprint on [min_z_m, max_z_m] (both planes), empty when neither plane is hit.
Box2d FootprintBounds(const View& view, double min_z_m, double max_z_m);

// Whether world point p projects inside the view's image and lies in front of it.
bool ViewSeesPoint(const View& view, const Eigen::Vector3d& point_in_world);

}  // namespace sacfuse
