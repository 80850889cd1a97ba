#pragma once
// Options of `sacfuse simulate`: a synthetic aerial block with known ground truth.
// Every field has its default and unit; `SimPreset()` fills them for a named preset.
#include <cstdint>
#include <string>
#include <vector>

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
};

// Preset names: "tiny" (seconds, for unit tests), "small" (demo), "medium", "dortmund" (16 nadir + 43 oblique
// views of 6132x8176 px at 10 cm GSD, about 1 km2). Throws ConfigError for an unknown name.
SimOptions SimPreset(const std::string& name);
std::vector<std::string> SimPresetNames();

}  // namespace sacfuse
