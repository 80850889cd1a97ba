#include "tiling/footprint.h"

namespace sacfuse {

std::optional<std::array<Eigen::Vector2d, 4>> GroundFootprint(const View& view, double ground_z_m) {
  const Rigid3d world_from_cam = view.cam_from_world.Inverse();
  const Eigen::Vector3d center = world_from_cam.translation;
  const double w = view.camera.width;
  const double h = view.camera.height;
  const std::array<Eigen::Vector2d, 4> corners = {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0),
                                                  Eigen::Vector2d(w, h), Eigen::Vector2d(0, h)};
  std::array<Eigen::Vector2d, 4> out;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d ray_in_world =
        world_from_cam.rotation * view.camera.Unproject(corners[i].x(), corners[i].y(), 1.0);
    if (std::abs(ray_in_world.z()) < 1e-12) return std::nullopt;
    const double t = (ground_z_m - center.z()) / ray_in_world.z();
    if (t <= 0) return std::nullopt;
    out[i] = (center + t * ray_in_world).head<2>();
  }
  return out;
}

Box2d FootprintBounds(const View& view, double min_z_m, double max_z_m) {
  Box2d b;
  for (double z : {min_z_m, max_z_m}) {
    if (auto fp = GroundFootprint(view, z)) {
      for (const auto& p : *fp) b.Extend(p);
    }
  }
  return b;
}

bool ViewSeesPoint(const View& view, const Eigen::Vector3d& point_in_world) {
  const Eigen::Vector3d p = view.cam_from_world * point_in_world;
  if (p.z() <= 0) return false;
  const Eigen::Vector2d uv = view.camera.Project(p);
  return uv.x() >= 0 && uv.y() >= 0 && uv.x() < view.camera.width && uv.y() < view.camera.height;
}

}  // namespace sacfuse
