#include "tools/bench/model_shift.h"

#include <cmath>

#include "core/error.h"

namespace sacfuse {

Eigen::Vector3d ColmapCameraCentre(const ColmapImage& image) {
  return -(image.cam_from_world_rotation.toRotationMatrix().transpose() * image.cam_from_world_translation);
}

Eigen::Vector3d ChooseModelOffset(const ColmapModel& model, double snap_m) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  size_t n = 0;
  if (!model.points3D.empty()) {
    for (const auto& [id, point] : model.points3D) sum += point.xyz;
    n = model.points3D.size();
  } else {
    for (const ColmapImage& image : model.images) sum += ColmapCameraCentre(image);
    n = model.images.size();
  }
  if (n == 0) throw Error("cannot choose a world offset for a sparse model with neither points nor images");
  const Eigen::Vector3d mean = sum / static_cast<double>(n);
  Eigen::Vector3d offset;
  for (int k = 0; k < 3; ++k) offset[k] = snap_m > 0 ? std::floor(mean[k] / snap_m) * snap_m : mean[k];
  return offset;
}

void ShiftColmapModel(ColmapModel* model, const Eigen::Vector3d& offset) {
  for (ColmapImage& image : model->images) {
    // cam = R * world + t = R * (world' + offset) + t = R * world' + (t + R * offset)
    image.cam_from_world_translation += image.cam_from_world_rotation.toRotationMatrix() * offset;
  }
  for (auto& [id, point] : model->points3D) point.xyz -= offset;
}

}  // namespace sacfuse
