#pragma once
// SfM-like sparse points for sparse/points3D.bin: candidates are random true-surface points (one per
// `sparse_area_per_point_m2`, at least `min_sparse_points`); while a view's TRUE depth is in memory, each candidate
// it sees (SeesPoint) becomes a keypoint of that image at its projection with the WRITTEN pose plus
// N(0, keypoint_sigma_px) noise (so reprojection errors are realistic). Candidates seen by >= 2 views become
// points3D with tracks; keypoints of the others stay untriangulated (point3D_id = -1), as in COLMAP.
// Observations with the TRUE pose are kept too, for the truth/ workspace.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/camera.h"
#include "core/raster.h"
#include "core/rigid3.h"
#include "io/colmap_model.h"
#include "tools/sim/surface.h"

namespace sacfuse::sim {

class SparsePointBuilder {
 public:
  SparsePointBuilder(const Surface& surface, const Box2d& area, int count, const Lighting& lighting, uint64_t key);

  // Adds the keypoints of view `view_index` (image_id = view_index + 1): to *written_points2D (WRITTEN pose)
  // and *true_points2D (TRUE pose; may be null).
  void ObserveView(uint32_t view_index, const DepthMap& true_depth, const PinholeCamera& depth_camera,
                   const PinholeCamera& image_camera, const Rigid3d& true_pose, const Rigid3d& written_pose,
                   double keypoint_sigma_px, std::vector<ColmapPoint2D>* written_points2D,
                   std::vector<ColmapPoint2D>* true_points2D);

  // Points seen by >= 2 views: fills model->points3D (ids from 1) and the point3D_id of their keypoints in
  // model->images (image i at position i, i.e. image_id = i + 1); error = RMS keypoint noise, pixels.
  // Returns the number of points.
  size_t Finish(ColmapModel* model) const;

  size_t num_candidates() const { return candidates_.size(); }

 private:
  struct Observation {
    uint32_t view;
    uint32_t point2D_idx;
    double sq_error_written;  // squared keypoint noise, pixels^2
  };
  struct Candidate {
    Eigen::Vector3d xyz;
    std::array<uint8_t, 3> rgb;
    std::vector<Observation> observations;
  };
  std::vector<Candidate> candidates_;
  uint64_t key_;
};

}  // namespace sacfuse::sim
