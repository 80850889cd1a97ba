#pragma once
// Plausibility of the cameras every input format reads (COLMAP text and binary models, OpenMVS .dmap headers,
// camera files): one rule for all, applied when the input is opened, so a NaN, infinite or absurd (1e300)
// number is an error naming the view and the file instead of a view that silently contributes nothing.
#include <string>

#include "core/camera.h"
#include "core/rigid3.h"

namespace sacfuse {

// Largest camera centre coordinate accepted, metres (Earth-centred coordinates are ~6.4e6 m, UTM northings 1e7).
constexpr double kMaxCameraCoordinateM = 1e8;
// Largest image side accepted, pixels.
constexpr int kMaxImageSidePx = 1000000;

// Throws InputError(file, who + ": ...") unless the size is 1..kMaxImageSidePx, both focal lengths are finite and
// within [0.01, 10000] x the larger image side (fields of view between ~0.006 and ~178 degrees), and the principal
// point is finite and within one image size of the image ([-w, 2w] x [-h, 2h]). `who` names the view.
void CheckViewIntrinsics(const PinholeCamera& camera, const std::string& file, const std::string& who);

// Throws InputError(file, who + ": ...") unless the rotation is a finite unit quaternion and the translation
// (equivalently the camera centre) is finite and within kMaxCameraCoordinateM of the origin.
void CheckViewPose(const Rigid3d& cam_from_world, const std::string& file, const std::string& who);

}  // namespace sacfuse
