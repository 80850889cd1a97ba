#pragma once
// `sacfuse eval`: accuracy, completeness and F1 of a result cloud against an airborne LiDAR reference, after
// ETH3D's protocol (Schöps et al. 2017; shared/reference/fusion-peers.md section 5) with the scanner-ray
// visibility model replaced by a top-surface model, as an airborne scanner sees everything from above.
//
// Definitions (tau = each threshold; v = voxel_m or gsd_m; grid cell c = top_cell_m or 4 x gsd_m):
//  * Mask: with a mask, only result and reference points whose XY lies inside count; the others are counted as
//    outside_mask. All reference points (inside or not) still serve as neighbours and build the top surface.
//  * Top-surface model: per XY cell of size c, the max and min reference z. top / bottom = max / min over the
//    cell and its 8 neighbours (so cells next to a wall take the roof height); occluder = max of the own cell's
//    top and, for each of the 4 opposite neighbour pairs, the lower top of the pair.
//  * Accuracy, per result point with nearest-reference distance d (3D, k-d tree): ACCURATE if d <= tau; else
//    UNOBSERVED (ignored) if no reference point lies in its 3 x 3 cells (no LiDAR there) or if
//    bottom - tau <= z < top - tau (hidden below the top surface: facades, under eaves or canopy); else
//    INACCURATE (floats in observed free space, is off the surface, or is sunk below every LiDAR return around
//    it). Primary accuracy = mean over voxels (edge v, 3D) holding >= 1 observed result point of the accurate
//    fraction in that voxel; raw accuracy = accurate / observed points.
//  * Completeness, over VISIBLE reference points (z >= occluder - max(tau, visible_margin_m)): ground under
//    canopy and returns below roofs are excluded, streets beside walls are kept. COMPLETE if the nearest result
//    point is within tau. Primary = mean over voxels of visible reference points of the complete fraction;
//    raw = complete / visible points.
//  * F1 = 2ac / (a + c), 0 when a + c = 0 (for primary and raw alike).
//  * Mean / median absolute distance: of the nearest-reference distance d over the result points observed at
//    the smallest threshold.
//  * Report-level counts partition the points at the smallest threshold: result_points = evaluated (observed) +
//    unobserved + outside_mask; reference_points_evaluated = visible reference points inside the mask.
//  * Points per m2 = result points inside the mask / area; area = mask area, or without a mask the area of the
//    top-surface cells holding reference points.
//  * Alignment (options.align): robust trimmed ICP (robust_icp.h) of the result onto the reference, applied to
//    every result point before scoring; `alignment` maps input result coordinates to aligned ones.
//
// Precision: points are held as float offsets from a double origin (the reference's min corner), so UTM
// coordinates lose nothing. Memory: ~40 bytes per result point and ~30 per reference point on top of the
// inputs; issue 4 will tile the evaluation for billion-point clouds.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "eval/dsm_accuracy.h"
#include "core/geo_mask.h"
#include "eval/eval_options.h"

namespace sacfuse {

struct ThresholdScore {
  double tau_m = 0.0;
  double accuracy = 0.0, completeness = 0.0, f1 = 0.0;              // density-normalised (primary), in [0, 1]
  double raw_accuracy = 0.0, raw_completeness = 0.0, raw_f1 = 0.0;  // plain point fractions (secondary)
  uint64_t result_observed = 0;       // result points inside the mask that are accurate or inaccurate
  uint64_t result_accurate = 0;
  uint64_t reference_visible = 0;     // reference points inside the mask visible to cameras
  uint64_t reference_complete = 0;
  uint64_t accuracy_voxels = 0;       // voxels averaged by the primary accuracy / completeness
  uint64_t completeness_voxels = 0;
};

struct EvalReport {
  std::vector<ThresholdScore> scores;  // one per threshold, ascending
  double mean_abs_distance_m = 0.0;
  double median_abs_distance_m = 0.0;
  uint64_t result_points = 0;         // scored (after the stride below)
  uint64_t result_points_in_file = 0;  // EvaluateLasFiles: all points of the file (0 = not from a file)
  uint64_t result_stride = 1;          // EvaluateLasFiles: every k-th point was scored (max_result_points)
  // Completeness was measured against every result point (streamed), not only the scored ones: a thinned cloud
  // leaves reference points without a result point within a small tau although the whole cloud covers them.
  bool completeness_from_all_points = false;
  uint64_t result_points_evaluated = 0;
  uint64_t result_points_unobserved = 0;
  uint64_t result_points_outside_mask = 0;
  uint64_t reference_points = 0;
  uint64_t reference_points_evaluated = 0;
  double area_m2 = 0.0;
  double points_per_m2 = 0.0;
  std::map<uint16_t, uint64_t> source_id_histogram;  // LAS point source ID -> result points
  bool aligned = false;
  Eigen::Matrix4d alignment = Eigen::Matrix4d::Identity();  // result_from_input, in the input CRS
  std::optional<DsmAccuracy> dsm;  // the DSM's accuracy when one was scored (eval/dsm_accuracy.h)
};

// Every point of a result cloud, in chunks: calls `chunk` once per chunk, in any order (for clouds too large to
// hold; see EvaluateClouds).
using ResultChunks = std::function<void(const std::function<void(const std::vector<Eigen::Vector3d>&)>& chunk)>;

// Pure API on in-memory points (coordinates in any metric CRS). result_source_ids is empty or one per result
// point. mask may be null. Throws ConfigError for bad options and Error for an empty reference, non-finite
// coordinates or mismatched sizes. `all_result_points` (optional): the whole cloud of which `result` is a thinned
// part; completeness is then measured against all of it, streamed (memory: one float per reference point), and
// accuracy on `result`.
EvalReport EvaluateClouds(const std::vector<Eigen::Vector3d>& result, const std::vector<uint16_t>& result_source_ids,
                          const std::vector<Eigen::Vector3d>& reference, const GeoMask* mask,
                          const EvalOptions& options, const ResultChunks& all_result_points = {});

// Reads both LAS files (and options.mask_path when set), then EvaluateClouds. Beyond options.max_result_points it
// scores accuracy on every k-th result point and completeness against all of them, read a second time in chunks.
// Throws InputError naming the bad file.
EvalReport EvaluateLasFiles(const std::string& result_las, const std::string& reference_las,
                            const EvalOptions& options);

// Human-readable table: one row per threshold plus the counts.
std::string FormatEvalTable(const EvalReport& report);

}  // namespace sacfuse
