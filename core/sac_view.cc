#include "core/sac_view.h"

namespace sacfuse {

SacView MakeSacView(const View& view, const DepthMap* depth, const SuperpixelMap* superpixels, const RgbImage* image,
                    const ConsistencyGraph* consistency) {
  SacView v;
  v.view = view;
  v.depth = depth;
  v.superpixels = superpixels;
  v.image = image;
  v.consistency = consistency;
  v.depth_camera = view.camera.Scaled(depth->width, depth->height);
  v.world_from_cam = view.cam_from_world.Inverse();
  return v;
}

DepthLookup LookupDepth(const SacView& view, const Eigen::Vector3d& point_in_world) {
  DepthLookup out;
  const Eigen::Vector3d p = view.view.cam_from_world * point_in_world;
  if (p.z() <= 0) return out;
  const Eigen::Vector2d uv = view.depth_camera.Project(p);
  if (!(uv.x() >= 0 && uv.y() >= 0 && uv.x() < view.depth->width && uv.y() < view.depth->height)) return out;
  out.inside = true;
  out.col = static_cast<int>(uv.x());
  out.row = static_cast<int>(uv.y());
  out.z_m = p.z();
  out.stored_depth_m = view.depth->at(out.row, out.col);
  return out;
}

}  // namespace sacfuse
