#pragma once
// A COLMAP dense workspace in a local world frame, for COLMAP's stereo_fusion: DEST/sparse holds a shifted copy
// of SOURCE/sparse (see model_shift.h; written in binary form, doubles kept exactly), DEST/images and DEST/stereo
// are symbolic links to SOURCE's (nothing is copied; the depth and normal maps are in camera frames and need no
// change). COLMAP writes its fused.ply into DEST.
#include <string>

#include <Eigen/Core>

namespace sacfuse {

struct ShiftedWorkspace {
  std::string path;              // DEST (absolute)
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // world = local + offset
  size_t images = 0;
  size_t points3D = 0;
};

// Creates or refreshes DEST. Throws InputError naming what is missing when SOURCE lacks sparse/, images/,
// stereo/fusion.cfg, stereo/depth_maps/ or stereo/normal_maps/ (stereo_fusion needs all of them), and Error when
// DEST/images or DEST/stereo exists and is not a symbolic link (nothing real is ever deleted).
ShiftedWorkspace PrepareShiftedWorkspace(const std::string& source_workspace, const std::string& dest_dir);

}  // namespace sacfuse
