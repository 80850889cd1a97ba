#include "tools/sim/sparse_points.h"

#include <algorithm>
#include <cmath>

#include "tools/sim/sim_random.h"
#include "tools/sim/visibility.h"

namespace sacfuse::sim {

SparsePointBuilder::SparsePointBuilder(const Surface& surface, const Box2d& area, int count, const Lighting& lighting,
                                       uint64_t key)
    : key_(key) {
  Rng rng(key);
  const Eigen::Vector3f up(0.0f, 0.0f, 1.0f);
  for (int k = 0; k < count; ++k) {
    const double x = rng.Uniform(area.min.x(), area.max.x()), y = rng.Uniform(area.min.y(), area.max.y());
    const double z = surface.Height(x, y);
    if (!std::isfinite(z)) continue;
    Candidate c;
    c.xyz = Eigen::Vector3d(x, y, z);
    const Eigen::Vector3f rgb = surface.Albedo(c.xyz, up) * lighting.Shade(up) * 255.0f;
    for (int i = 0; i < 3; ++i) c.rgb[i] = static_cast<uint8_t>(std::clamp(std::lround(rgb[i]), 0L, 255L));
    candidates_.push_back(c);
  }
}

void SparsePointBuilder::ObserveView(uint32_t view_index, const DepthMap& true_depth, const PinholeCamera& depth_camera,
                                     const PinholeCamera& image_camera, const Rigid3d& true_pose,
                                     const Rigid3d& written_pose, double keypoint_sigma_px,
                                     std::vector<ColmapPoint2D>* written_points2D,
                                     std::vector<ColmapPoint2D>* true_points2D) {
  for (size_t i = 0; i < candidates_.size(); ++i) {
    Candidate& c = candidates_[i];
    if (!SeesPoint(true_depth, depth_camera, true_pose, c.xyz)) continue;
    const uint64_t k = Hash3(key_, view_index, i);
    const Eigen::Vector2d noise(keypoint_sigma_px * HashToNormal(k), keypoint_sigma_px * HashToNormal(k + 1));
    const Eigen::Vector2d xy_written = image_camera.Project(written_pose * c.xyz) + noise;
    const Eigen::Vector2d xy_true = image_camera.Project(true_pose * c.xyz) + noise;
    // A keypoint pushed outside the image by the pose error is not detected.
    if (xy_written.x() < 0.0 || xy_written.y() < 0.0 || xy_written.x() >= image_camera.width ||
        xy_written.y() >= image_camera.height) {
      continue;
    }
    ColmapPoint2D p;
    p.xy = xy_written;
    c.observations.push_back({view_index, static_cast<uint32_t>(written_points2D->size()), noise.squaredNorm()});
    written_points2D->push_back(p);
    if (true_points2D != nullptr) {
      p.xy = xy_true;
      true_points2D->push_back(p);
    }
  }
}

size_t SparsePointBuilder::Finish(ColmapModel* model) const {
  uint64_t next_id = 1;
  for (const Candidate& c : candidates_) {
    if (c.observations.size() < 2) continue;
    ColmapPoint3D p;
    p.point3D_id = next_id++;
    p.xyz = c.xyz;
    p.rgb = c.rgb;
    double sum = 0.0;
    for (const Observation& o : c.observations) {
      p.track.push_back({o.view + 1, o.point2D_idx});
      sum += o.sq_error_written;
      if (o.view < model->images.size() && o.point2D_idx < model->images[o.view].points2D.size()) {
        model->images[o.view].points2D[o.point2D_idx].point3D_id = p.point3D_id;
      }
    }
    p.error = std::sqrt(sum / c.observations.size());
    model->points3D.emplace(p.point3D_id, std::move(p));
  }
  return next_id - 1;
}

}  // namespace sacfuse::sim
