#pragma once
// Robust rigid ICP of a result cloud onto the reference (the paper registers its clouds to the LiDAR with a
// robust ICP before scoring). Works in the local frame of the evaluation, in double precision on a seeded random
// subsample of the result.
//
// Per iteration: nearest reference neighbour of every subsample point; pairs farther than align_max_distance_m
// dropped; the closest align_trim_fraction kept (trimmed ICP); Huber weights with threshold 1.345 x the robust
// sigma (1.4826 x median residual) on what is left; then one rigid update about the subsample centroid:
//   point_to_plane: damped Gauss-Newton on sum w (n . (R p + t - q))^2, reference normals from a PCA of the
//                   10 nearest reference points (degrees of freedom the scene does not constrain stay put);
//   point_to_point: weighted Kabsch/Umeyama (SVD, no scale).
// Stops when an update moves the centroid of the kept pairs by < 0.1 mm and rotates by < 1e-6 rad, or after
// align_max_iterations. point_to_point slides only slowly along nadir-sampled planes (~100 iterations for a
// 0.5 m offset where point_to_plane needs < 10), hence point_to_plane is the default.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "eval/eval_options.h"
#include "eval/point_index.h"

namespace sacfuse {

struct IcpResult {
  Eigen::Matrix4d result_from_input = Eigen::Matrix4d::Identity();  // local frame
  int iterations = 0;
  bool converged = false;
  size_t correspondences = 0;  // pairs used in the last iteration
  double rms_m = 0.0;          // weighted RMS residual of the last iteration, metres
};

// `use` (null = all) selects the result points the subsample is drawn from (e.g. those inside the mask).
IcpResult AlignRobustIcp(const std::vector<Eigen::Vector3f>& result, const std::vector<uint8_t>* use,
                         const std::vector<Eigen::Vector3f>& reference, const PointIndex& reference_index,
                         const EvalOptions& options);

}  // namespace sacfuse
