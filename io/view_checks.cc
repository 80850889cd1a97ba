#include "io/view_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace sacfuse {
namespace {

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}

bool Within(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

}  // namespace

void CheckViewIntrinsics(const PinholeCamera& camera, const std::string& file, const std::string& who) {
  const auto fail = [&](const std::string& what) { throw InputError(file, who + ": " + what); };
  if (camera.width < 1 || camera.height < 1 || camera.width > kMaxImageSidePx || camera.height > kMaxImageSidePx) {
    fail("implausible image size " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
         " (each side must be 1.." + std::to_string(kMaxImageSidePx) + " px)");
  }
  const double side = std::max(camera.width, camera.height);
  if (!Within(camera.fx, 0.01 * side, 1e4 * side) || !Within(camera.fy, 0.01 * side, 1e4 * side)) {
    fail("implausible focal length fx " + Num(camera.fx) + ", fy " + Num(camera.fy) + " px (must be finite and in [" +
         Num(0.01 * side) + ", " + Num(1e4 * side) + "] px for a " + std::to_string(camera.width) + "x" +
         std::to_string(camera.height) + " image)");
  }
  if (!Within(camera.cx, -camera.width, 2.0 * camera.width) ||
      !Within(camera.cy, -camera.height, 2.0 * camera.height)) {
    fail("implausible principal point (" + Num(camera.cx) + ", " + Num(camera.cy) +
         ") px (must be finite and within one image size of the " + std::to_string(camera.width) + "x" +
         std::to_string(camera.height) + " image)");
  }
}

void CheckViewPose(const Rigid3d& cam_from_world, const std::string& file, const std::string& who) {
  const Eigen::Quaterniond& q = cam_from_world.rotation;
  if (!q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 1e-6) {
    throw InputError(file, who + ": camera rotation (quaternion w x y z = " + Num(q.w()) + " " + Num(q.x()) + " " +
                               Num(q.y()) + " " + Num(q.z()) + ") is not a finite unit quaternion");
  }
  const Eigen::Vector3d& t = cam_from_world.translation;
  if (!t.allFinite() || t.cwiseAbs().maxCoeff() > kMaxCameraCoordinateM) {
    throw InputError(file, who + ": implausible camera position (translation " + Num(t.x()) + " " + Num(t.y()) + " " +
                               Num(t.z()) + " m; each coordinate must be finite and within +-" +
                               Num(kMaxCameraCoordinateM) + " m)");
  }
}

}  // namespace sacfuse
