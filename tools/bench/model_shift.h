#pragma once
// Moving a COLMAP sparse model to a local world frame, so programs that compute in float32 (COLMAP's
// stereo_fusion: its projection matrices and fused.ply) keep millimetres on UTM-sized coordinates.
// world' = world - offset: each image's cam_from_world translation becomes t + R * offset (the camera frames and
// therefore the depth and normal maps are unchanged), points3D move by -offset, cameras stay as they are.
#include <string>

#include <Eigen/Core>

#include "io/colmap_model.h"

namespace sacfuse {

// The offset to subtract: the mean of the sparse points (the camera centres when there are none), each
// coordinate floored to a multiple of `snap_m` (1000 m: the same snapping as the LAS writer's offset).
// Throws Error for a model with neither points nor images.
Eigen::Vector3d ChooseModelOffset(const ColmapModel& model, double snap_m = 1000.0);

// Applies world' = world - offset to every image pose and sparse point.
void ShiftColmapModel(ColmapModel* model, const Eigen::Vector3d& offset);

// Camera centre of an image in its model's world frame: -R^T t.
Eigen::Vector3d ColmapCameraCentre(const ColmapImage& image);

}  // namespace sacfuse
