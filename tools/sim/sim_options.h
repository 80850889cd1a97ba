#pragma once
// Options of `sacfuse simulate`: a synthetic aerial block with known ground truth.
// Every field has its default and unit; `SimPreset()` fills them for a named preset.
#include <cstdint>
#include <string>
#include <vector>

#include "tools/sim/sgbm_options.h"

namespace sacfuse {

// Switchable, seeded error models applied to the rendered (true) depth maps and poses. Each magnitude is for a
// NADIR view; obliques get `oblique_factor` times more of the stereo noise, bias and blunders.
struct SimErrorOptions {
  bool enabled = true;                   // master switch (false = perfect depth, true poses: the "ceiling")
  // Pose error: the pose written to the workspace differs from the one used to render, so every depth map is
  // rigidly biased when back-projected with the written pose.
  double pose_position_sigma_m = 0.05;   // per axis, metres
  double pose_rotation_sigma_deg = 0.005;  // per axis, degrees
  // Stereo noise, sigma_z = z^2 * sigma_disparity / (f * B), spatially correlated (Gaussian-blurred white noise
  // renormalised to that sigma).
  double disparity_sigma_px = 0.3;       // pixels
  double stereo_baseline_m = 0.0;        // 0 = derived from forward overlap (distance to the next exposure)
  double noise_correlation_px = 3.0;     // Gaussian blur sigma of the noise field, pixels
  // Smooth low-frequency bias field per view (a few cosine modes across the image), peak amplitude in metres.
  double bias_amplitude_m = 0.10;
  // Foreground fattening: foreground depth spreads this many pixels into the background at depth edges.
  int fattening_px = 2;
  double fattening_min_step_m = 1.0;     // depth jump that counts as an edge, metres
  // Blunders: blobs of wrong depth.
  double blunders_per_mpx = 20.0;        // blobs per million pixels
  double blunder_radius_px = 6.0;        // mean blob radius, pixels
  double blunder_depth_sigma_m = 3.0;    // depth offset of a blob, metres
  // Invalid pixels where a left-right check would fail: occlusion strips behind depth edges and dropouts.
  int occlusion_strip_px = 3;
  double dropout_fraction = 0.02;        // fraction of pixels dropped in small clusters
  double oblique_factor = 1.5;           // obliques are this much noisier
  double scale = 1.0;                    // multiplies every magnitude above (2-3 = harsher, closer to real)
  // --- Added by the sim module ---
  // Sparse (SfM-like) observations: points2D = projection with the WRITTEN pose + N(0, this) per axis, pixels.
  double keypoint_sigma_px = 0.5;
};

struct SimOptions {
  std::string preset = "tiny";
  uint64_t seed = 1;
  // Scene.
  std::string scene = "city";            // "city" (procedural) or "las" (from a LiDAR file, see from_las)
  std::string from_las;                  // path of an airborne LAS used as the surface when scene == "las"
  double area_width_m = 60.0;            // extent of the scene in x (east), metres
  double area_height_m = 60.0;           // extent in y (north), metres
  double origin_east_m = 390000.0;       // south-west corner of the scene in the project CRS
  double origin_north_m = 5705000.0;
  double ground_height_m = 100.0;        // mean terrain height, metres
  std::string crs = "EPSG:25832";        // ETRS89 / UTM 32N (Dortmund)
  // Camera block: one nadir and four 45-degree obliques (forward, backward, left, right) per exposure.
  bool obliques = true;
  double oblique_tilt_deg = 45.0;
  double gsd_m = 0.10;                   // nadir ground sampling distance at ground height, metres
  int nadir_width_px = 320;              // nadir image size; obliques use height x width (rotated sensor)
  int nadir_height_px = 240;
  double nadir_focal_mm = 50.0;
  double oblique_focal_mm = 80.0;
  double pixel_size_um = 6.0;
  double forward_overlap = 0.75;         // fraction of the nadir footprint along track
  double side_overlap = 0.80;            // fraction across track
  int max_nadir_views = 0;               // 0 = as many as the overlaps give; else keep the ones nearest the centre
  int max_oblique_views = 0;             // likewise for obliques
  int depth_downsample = 1;              // depth maps at image size / this factor
  double reference_density_pts_m2 = 10.0;  // LiDAR-like reference sampling of the true surface
  SimErrorOptions errors;

  // --- Added by the sim module (defaults keep the behaviour described in simulate.h) ---
  bool write_truth = false;              // also write truth/: TRUE poses and error-free depth maps (the ceiling)
  double truth_ortho_cell_m = 0.0;       // > 0: also write truth_ortho.tif, the reference ortho (truth_ortho.h)
  double eval_cell_m = 0.0;              // eval_mask.png cell, metres (0 = 1 m, halved while the shorter area side
                                         // has < 100 cells, down to 0.25 m)
  double sparse_area_per_point_m2 = 20.0;  // one sparse-point candidate per this much area, m^2
  int min_sparse_points = 300;           // ... but at least this many candidates
  int jpeg_quality = 92;                 // images/*.jpg, 1..100
  double sun_azimuth_deg = 135.0;        // Lambert shading: sun azimuth, degrees clockwise from north
  double sun_elevation_deg = 50.0;       // sun elevation above the horizon, degrees
  double ambient = 0.35;                 // ambient share of the light, 0..1
  double city_rotation_deg = 15.0;       // street grid of the procedural city against east, degrees
  double las_cell_m = 0.0;               // DSM cell of a --from-las scene, metres (0 = from the point density)
  // Also write stereo/consistency_graphs/<name>.geometric.bin (COLMAP's patch_match_stereo with
  // --PatchMatchStereo.write_consistency_graph 1; input of SAC's dense-correspondence strategy), computed after
  // all depth maps by reprojecting every valid pixel into up to 20 overlapping views (consistency_graphs.h).
  // On for tiny; off for small (1.1 GB, ~14 s), medium and dortmund: the pass costs about 20 reprojections per depth pixel
  // and holds 21 depth maps in memory (about 4 GB at dortmund size), and the graphs are a few bytes per pixel.
  bool write_consistency_graphs = true;
  // stereo/normal_maps/ (COLMAP's normals, 3 floats per depth pixel: three times the depth maps' size). sacfuse
  // itself does not read them (SAC fits its own normals); COLMAP's stereo_fusion needs them. Off saves 36 GB at
  // dortmund size.
  bool write_normal_maps = true;
  // Where the depth maps come from: "synthetic" (the true depth plus the error models of SimErrorOptions) or "sgbm"
  // (OpenCV's StereoSGBM on rectified pairs of the rendered images under the WRITTEN poses, tools/sim/sgbm_depth.h:
  // a real matcher's errors with exact truth; the pose errors and every other output stay as they are).
  std::string depth = "synthetic";
  sim::SgbmDepthOptions sgbm;            // depth == "sgbm"
};

// Preset names (details in sim_options.cc): "tiny" (60 m, 20 views of 320x240 px at 20 cm GSD; about a second,
// for unit tests), "small" (the demo: 130 m, 56 views of 800x600 px at 10 cm), "medium" (400 m, 100 views of
// 2000x1500 px), "dortmund" (16 nadir + 43 oblique views of 6132x8176 px at 10 cm GSD, about 1 km2).
// Throws ConfigError for an unknown name.
SimOptions SimPreset(const std::string& name);
// The same flight over the same scene at `factor` times the image size: image sides x factor, pixel pitch and GSD
// / factor (so the flying height and footprints stay); the reference cloud keeps its density.
void ScaleSimPixels(double factor, SimOptions* options);
std::vector<std::string> SimPresetNames();

}  // namespace sacfuse
