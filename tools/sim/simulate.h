#pragma once
// `sacfuse simulate`: a synthetic aerial block with known ground truth, written as a COLMAP 3.8 dense workspace
// (so COLMAP's own stereo_fusion could run on it) plus the evaluation inputs. Layout of out_dir:
//   images/<kind>/<exposure>.jpg           rendered RGB (JPEG, jpeg_quality), kind = nadir, oblique_fwd, ...
//   sparse/{cameras,images,points3D}.bin   PINHOLE camera per view, the WRITTEN (erroneous) poses, sparse points
//                                          with tracks (see sparse_points.h)
//   stereo/depth_maps/<name>.geometric.bin  z-depth (float32, 0 = invalid) with the error models of
//                                          depth_errors.h, or (depth: sgbm) matched from the images by
//                                          StereoSGBM (sgbm_workspace.h), at image size / depth_downsample
//   stereo/normal_maps/<name>.geometric.bin camera-frame unit normals from that depth (depth_normals.h)
//   stereo/consistency_graphs/<name>.geometric.bin (write_consistency_graphs) COLMAP dense-matching consistency
//                                          of the written depth and poses (consistency_graphs.h)
//   stereo/fusion.cfg, stereo/patch-match.cfg
//   reference.las                          LAS 1.4 reference (reference_cloud.h)
//   eval_mask.png (+ .json sidecar)        cells whose true surface point >= 2 views see (visibility.h)
//   metadata.json                          options, CRS, area, per view: kind, intrinsics, TRUE and WRITTEN poses
//                                          and centres, error realisations, file names
//   truth/ (write_truth)                   the same workspace with TRUE poses and error-free depth; images are
//                                          relative symlinks
// Views are generated one at a time (streaming), each with OpenMP inside; memory is bounded by one view.
#include <cstdint>
#include <functional>
#include <string>

#include "tools/sim/sim_options.h"

namespace sacfuse {

struct SimSummary {
  int num_views = 0;
  int num_nadir = 0;
  int num_oblique = 0;
  uint64_t depth_pixels = 0;      // valid depth pixels written (all views)
  uint64_t reference_points = 0;
  uint64_t sparse_points = 0;     // points3D (seen by >= 2 views)
  int consistency_graphs = 0;     // stereo/consistency_graphs files written (0 unless write_consistency_graphs)
  double seconds = 0.0;
  std::string workspace_dir;      // out_dir
  std::string reference_las;
  std::string eval_mask_png;
  std::string metadata_json;
};

// stage: "plan", "scene", "reference", "views", "sparse", "sgbm" (depth: sgbm), "consistency"
// (write_consistency_graphs), "done".
using SimProgress = std::function<void(const std::string& stage, size_t done, size_t total)>;

// Throws ConfigError listing every broken rule as "sim.<key> = <value>: <rule>".
void ValidateSimOptions(const SimOptions& options);

// Validates, builds the scene (procedural city or --from-las DSM), plans the flight and writes out_dir.
// Throws ConfigError / InputError / Error with the context.
SimSummary SimulateBlock(const SimOptions& options, const std::string& out_dir, const SimProgress& progress = {});

namespace sim {

class Surface;

// The scene SimulateBlock simulates; tests pass their own (e.g. a plane with one box).
struct SceneSpec {
  const Surface* surface = nullptr;
  double area_x0 = 0.0, area_y0 = 0.0, area_x1 = 0.0, area_y1 = 0.0;  // simulated area, project CRS metres
  double ground_z = 0.0;        // mean ground height (flying height reference), metres
  std::string crs;              // written to metadata and the mask sidecar
  std::string kind = "custom";  // "city", "las", "custom"
};

SimSummary SimulateScene(const SimOptions& options, const SceneSpec& scene, const std::string& out_dir,
                         const SimProgress& progress = {});

}  // namespace sim
}  // namespace sacfuse
