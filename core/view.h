#pragma once
// One oriented view of the block: an undistorted camera, its pose, and where its rasters live.
#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/rigid3.h"

namespace sacfuse {

struct View {
  uint32_t index = 0;       // 0-based position in the block; LAS point source ID = index + 1
  std::string name;         // image name as the input names it (may contain sub-folders)
  PinholeCamera camera;     // intrinsics at IMAGE resolution
  Rigid3d cam_from_world;   // pose; world = project CRS (metres)
  // Indices of the views whose depth maps were matched in one image pair with this one (either direction), sorted;
  // empty when the input does not say (COLMAP's stereo/patch-match.cfg naming each view's sources says).
  std::vector<uint32_t> matching_partners;

  Eigen::Vector3d CenterInWorld() const { return cam_from_world.Inverse().translation; }
  // Unit viewing direction (camera +z axis) in the world frame.
  Eigen::Vector3d ViewDirectionInWorld() const {
    return cam_from_world.rotation.conjugate() * Eigen::Vector3d::UnitZ();
  }
};

}  // namespace sacfuse
