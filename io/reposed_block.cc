#include "io/reposed_block.h"

#include "core/error.h"

namespace sacfuse {

ReposedBlock::ReposedBlock(std::unique_ptr<DepthBlock> inner, const std::vector<Rigid3d>& cam_from_world,
                           double scene_height_shift_m)
    : inner_(std::move(inner)), views_(inner_->views()), scene_height_shift_m_(scene_height_shift_m) {
  if (cam_from_world.size() != views_.size()) {
    throw Error(inner_->source() + ": " + std::to_string(cam_from_world.size()) + " poses for " +
                std::to_string(views_.size()) + " views");
  }
  for (size_t i = 0; i < views_.size(); ++i) views_[i].cam_from_world = cam_from_world[i];
}

std::vector<double> ReposedBlock::SceneHeights() const {
  std::vector<double> z = inner_->SceneHeights();
  for (double& h : z) h += scene_height_shift_m_;
  return z;
}

std::unique_ptr<DepthBlock> WithWorldOrigin(std::unique_ptr<DepthBlock> input, const Eigen::Vector3d& origin_m) {
  if (origin_m.isZero()) return input;
  std::vector<Rigid3d> poses;
  poses.reserve(input->views().size());
  for (const View& v : input->views()) {
    // cam_from_new_world = cam_from_world * world_from_new_world, world = new world - origin; the centre is
    // computed and moved directly so that it moves by origin_m to the last bit.
    const Eigen::Vector3d centre = v.CenterInWorld() + origin_m;
    poses.push_back(Rigid3d{v.cam_from_world.rotation, -(v.cam_from_world.rotation * centre)});
  }
  return std::make_unique<ReposedBlock>(std::move(input), poses, origin_m.z());
}

}  // namespace sacfuse
