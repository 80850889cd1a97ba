#include "config/option_table.h"

#include <string>
#include <utility>

#include "core/depth_edge.h"

namespace sacfuse {
namespace {

constexpr uint32_t kSac = MethodScope(FusionMethodKind::kSac);
constexpr uint32_t kConsistency = MethodScope(FusionMethodKind::kConsistency);
constexpr uint32_t kDisparityNormal = MethodScope(FusionMethodKind::kDisparityNormal);
constexpr uint32_t kTsdf = MethodScope(FusionMethodKind::kTsdf);
constexpr uint32_t kMultiray = MethodScope(FusionMethodKind::kMultiray);
// The methods that reproject into neighbour views chosen by fusion.max_neighbor_views, max_view_angle_deg and
// min_footprint_overlap: SAC (core/view_neighbors.h) and, through the block's view plan (jobs/method_geometry.h,
// FusionScope::plan), consistency, disparity_normal and multiray. tsdf gets the plan too but reads only its GSD.
constexpr uint32_t kNeighbourViews = kSac | kConsistency | kDisparityNormal | kMultiray;

// A key whose value changes the points (part of ResultSettingsText, the resume hash of tiled runs).
OptionSpec Affects(const char* unit, OptionRange range, uint32_t scopes = kEveryScope) {
  return OptionSpec{unit, std::move(range), true, scopes};
}
// A key that says where files go, how to run or how to score, never which points are written.
OptionSpec Neutral(const char* unit, OptionRange range) {
  return OptionSpec{unit, std::move(range), false, kEveryScope};
}

// A list whose items obey `item` and that must not be empty.
OptionRange Required(OptionRange item) {
  item.required = true;
  return item;
}

std::vector<std::pair<FusionMethodKind, std::string>> MethodChoices() {
  std::vector<std::pair<FusionMethodKind, std::string>> choices;
  for (const FusionMethodName& m : FusionMethodNames()) choices.emplace_back(m.kind, m.name);
  return choices;
}

}  // namespace

// The single place where YAML keys meet struct fields: per key its field, unit, range or choices, whether it
// changes the points, the methods that read it (default: all), and its doc (which names the unit and rule in
// words for --print-defaults).
ConfigSchema MakeOptionTable(JobConfig* c) {
  ConfigSchema s;
  s.AddString("crs", &c->crs, Affects("-", AnyText()),
              "project CRS of the coordinates (through PROJ), written into every LAS: \"\" = none (local metres) | "
              "a projected CRS in metres, e.g. EPSG:25832 (z = ellipsoidal height) | projected + vertical for "
              "orthometric heights, e.g. EPSG:2154+5720 | WKT1, WKT2, PROJJSON | ENU:lat,lon,h (local "
              "east-north-up frame at that origin; degrees, metres)");
  s.AddString("input.format", &c->input.format, Affects("-", Choices({"colmap", "openmvs", "rasters"})),
              "input kind: colmap (a COLMAP dense workspace) | openmvs (a folder of OpenMVS depth%04u.dmap files) "
              "| rasters (float32 TIFF depth rasters + a camera file, see input.cameras)");
  s.AddString("input.path", &c->input.path, Affects("-", RequiredText()),
              "input folder (relative to this file); required");
  s.AddString("input.depth_type", &c->input.depth_type, Affects("-", Choices({"geometric", "photometric"})),
              "COLMAP depth maps to fuse: geometric | photometric");
  s.AddString("input.cameras", &c->input.cameras, Affects("-", AnyText()),
              "rasters: camera file (.yaml/.yml/.csv, relative to this file); empty = cameras.yaml, cameras.yml or "
              "cameras.csv in input.path");
  s.AddString("input.depth_kind", &c->input.depth_kind, Affects("-", Choices({"z", "range"})),
              "rasters: depth values are z (along the optical axis) | range (distance along the pixel's ray), metres");
  s.AddDoubleList("input.origin_m", &c->input.origin_m, Affects("m", Required(AnyNumber())),
                  "[east, north, height] added to the input's coordinates (poses, camera-file x_m/y_m/z_m) to give "
                  "CRS coordinates: a workspace shifted to a local origin; metres, 3 numbers");
  s.AddString("input.cameras_crs", &c->input.cameras_crs, Affects("-", AnyText()),
              "rasters: CRS of the camera file's positions (projected, compound or geographic; as crs), "
              "transformed into crs through PROJ; empty = crs");
  s.AddString("output.dir", &c->output.dir, Neutral("-", RequiredText()), "output folder (relative to this file)");
  s.AddString("output.format", &c->output.format, Neutral("-", Choices({"laz", "las", "copc"})),
              "point cloud format: laz (DIR/fused.laz, LASzip-compressed, 50,000-point chunks) | las (DIR/fused.las, "
              "uncompressed) | copc (DIR/fused.copc.laz, a Cloud Optimized Point Cloud viewers stream; LAS 1.4 "
              "only; built out of core within resources.memory_gb). Tiled runs write their tiles as LAZ "
              "(tiles/<id>.laz), as COPC for copc (tiles/<id>.copc.laz), and a tile index DIR/tiles.vpc");
  s.AddString("output.las_version", &c->output.las_version, Affects("-", Choices({"1.4", "1.2"})),
              "LAS version: 1.4 (point format 7) | 1.2 (format 3)");
  s.AddDouble("output.scale_m", &c->output.scale_m, Affects("m", Closed(1e-6, 1.0)),
              "LAS coordinate quantum, metres; 10^k x {1, 0.5, 0.25}");
  // The DSM's keys never change the points; what a tile's DSM window depends on enters the resume hash through
  // ResultSettingsText (config/result_settings.cc) only when the run writes a DSM.
  s.AddString("output.dsm", &c->output.dsm, Neutral("-", Choices({"auto", "on", "off"})),
              "DSM raster DIR/dsm.tif (float32 Cloud Optimized GeoTIFF): auto (on when crs is set) | on | off");
  s.AddDouble("output.dsm_cell_m", &c->output.dsm_cell_m, Neutral("m", Closed(0, 1000)),
              "DSM cell edge, metres; 0 = 2 x the block's GSD rounded to 1, 2, 2.5 or 5 x 10^k; must divide "
              "tiling.tile_size_m");
  s.AddDouble("output.dsm_max_hole_m", &c->output.dsm_max_hole_m, Neutral("m", Closed(0, 1000)),
              "DSM holes up to this size, metres on each side, are filled from their rim; larger ones stay nodata "
              "(0 = none filled)");
  s.AddString("output.raster_layout", &c->output.raster_layout, Neutral("-", Choices({"auto", "single", "tiles"})),
              "raster products: single (one COG) | tiles (COG blocks in DIR/dsm/ + DIR/dsm.vrt, DIR/ortho/ + DIR/ortho.vrt) "
              "| auto (tiles "
              "beyond 2^30 cells)");
  s.AddString("output.ortho", &c->output.ortho, Neutral("-", Choices({"auto", "on", "off"})),
              "true orthophoto DIR/ortho.tif (RGBA 8-bit Cloud Optimized GeoTIFF on the DSM's cells, each cell from "
              "an original image of the view SAC selected, occlusion tested against the DSM): auto (on when the "
              "DSM is written) | on | off");
  CoregistrationOptions& co = c->coregistration;  // every method: a block-level stage before tiling
  s.AddBool("coregistration.enabled", &co.enabled, Affects("-", {}),
            "correct every view's pose against its neighbours' depth maps before fusion (core/coregistration.h)");
  s.AddInt("coregistration.max_pixels_per_view", &co.max_pixels_per_view, Affects("px", Closed(1000, 100000000)),
           "depth maps are decimated (every k-th pixel, k odd) to at most this many pixels; 1000-1e8");
  s.AddInt("coregistration.samples_per_view", &co.samples_per_view, Affects("px", Closed(100, 100000000)),
           "samples of each view projected into its neighbours, at most; 100-1e8");
  s.AddInt("coregistration.iterations", &co.iterations, Affects("steps", Closed(1, 50)),
           "damped Gauss-Newton steps, each projecting again; 1-50");
  s.AddInt("coregistration.max_neighbor_views", &co.max_neighbor_views, Affects("views", Closed(1, 256)),
           "views each view is compared with (footprint overlap x cos angle, best first); 1-256");
  s.AddDouble("coregistration.max_view_angle_deg", &co.max_view_angle_deg, Affects("deg", Closed(0, 180)),
              "views whose viewing directions differ by more are not compared, degrees; 0-180");
  s.AddDouble("coregistration.huber_gsd", &co.huber_gsd, Affects("GSD", Above(0)),
              "Huber threshold of the point-to-plane residuals, local GSDs; > 0");
  s.AddDouble("coregistration.max_residual_gsd", &co.max_residual_gsd, Affects("GSD", Above(0)),
              "residuals larger than this are left out, local GSDs; > 0");
  s.AddEnum("fusion.method", &c->fusion.method, MethodChoices(), Affects("-", {}),
            "fusion method: sac (Select-and-Combine) | union (every valid depth pixel: the 'before fusion' baseline) "
            "| the paper's comparison methods: consistency ([15]: occluded and redundant depths removed) | "
            "disparity_normal ([13]: disparity + normal consistency, averaged) | tsdf ([7]: truncated signed "
            "distance on a sparse voxel grid) | multiray ([35]: correspondence groups triangulated from all rays)");
  SacOptions& f = c->fusion.sac;
  s.AddInt("fusion.max_neighbor_views", &f.max_neighbor_views, Affects("views", Closed(1, 64), kNeighbourViews),
           "neighbour views per view (by footprint overlap)");
  s.AddDouble("fusion.max_view_angle_deg", &f.max_view_angle_deg, Affects("deg", Closed(0, 180), kNeighbourViews),
              "max angle between neighbours' view directions, deg");
  s.AddDouble("fusion.min_footprint_overlap", &f.min_footprint_overlap, Affects("-", Closed(0, 1), kNeighbourViews),
              "min shared fraction of a footprint, 0-1");
  s.AddString("fusion.correspondence", &f.correspondence,
              Affects("-", Choices({"reprojection", "proximity", "dense"}), kSac),
              "point groups: reprojection | proximity (3D radius) | dense (input's dense matches)");
  s.AddDouble("fusion.depth_tolerance_gsd", &f.depth_tolerance_gsd, Affects("GSD", Above(0), kSac),
              "depth agreement tolerance, in local GSDs");
  s.AddDouble("fusion.depth_tolerance_rel", &f.depth_tolerance_rel, Affects("-", Closed(0, 0.5), kSac),
              "plus this fraction of the depth, 0-0.5");
  s.AddDouble("fusion.proximity_radius_m", &f.proximity_radius_m, Affects("m", AtLeast(0), kSac),
              "proximity search radius, m; 0 = 1.5 superpixels");
  s.AddDouble("fusion.tau_m", &f.tau_m, Affects("m", Above(0), kSac), "Netlet edge threshold tau, metres (paper: 2)");
  s.AddString("fusion.netlets", &f.netlets, Affects("-", Choices({"node", "partition"}), kSac),
              "Netlets: node (one per node, Algorithm 1) | partition (disjoint)");
  s.AddString("fusion.unary", &f.unary, Affects("-", Choices({"quality", "paper"}), kSac),
              "unary term: quality | paper (constant)");
  s.AddDouble("fusion.quality_weight", &f.quality_weight, Affects("-", AtLeast(0), kSac),
              "quality unary: weight of relative stereo depth uncertainty (z^2/f)");
  s.AddDouble("fusion.min_incidence_cos", &f.min_incidence_cos, Affects("-", Closed(0.01, 1), kSac),
              "quality unary: floor of cos(incidence), 0.01-1");
  s.AddDouble("fusion.agreement_weight", &f.agreement_weight, Affects("-", AtLeast(0), kSac),
              "quality unary: weight of disagreement");
  s.AddDouble("fusion.agreement_tolerance_gsd", &f.agreement_tolerance_gsd, Affects("GSD", Above(0), kSac),
              "quality unary: stricter 'views agree' tolerance, local GSDs");
  s.AddDouble("fusion.displacement_weight", &f.displacement_weight, Affects("-", AtLeast(0), kSac),
              "quality unary: weight of node displacement");
  s.AddDouble("fusion.smoothness_weight", &f.smoothness_weight, Affects("-", AtLeast(0), kSac),
              "smoothness between adjacent clusters (0 = off)");
  s.AddInt("fusion.smoothness_rounds", &f.smoothness_rounds, Affects("rounds", Closed(0, 20), kSac),
           "rounds of that smoothness");
  s.AddString("fusion.collapse", &f.collapse, Affects("-", Choices({"netlet", "best_view", "none"}), kSac),
              "collapse: netlet (drop pixels the Netlet's chosen view emits) | best_view (also those a more precise "
              "view holds) | none (keep every view's pixels that pass their own tests: for a stereo matcher's depth "
              "maps)");
  s.AddDouble("fusion.redundancy_tolerance_sigmas", &f.redundancy_tolerance_sigmas, Affects("sigma", AtLeast(0), kSac),
              "best_view: 'same surface' also within this many sigmas of estimated noise (0 = strict tolerance)");
  s.AddInt("fusion.free_space_min_views", &f.free_space_min_views, Affects("views", Closed(0, 64), kSac),
           "free space: drop points that at least this many views see through (0 = off)");
  s.AddDouble("fusion.free_space_sigmas", &f.free_space_sigmas, Affects("sigma", AtLeast(0), kSac),
              "free space: 'sees through' beyond this many sigmas of the estimated noise");
  s.AddInt("fusion.free_space_early_pass_views", &f.free_space_early_pass_views, Affects("views", Closed(0, 64), kSac),
           "free space: a point none of the first this many judges sees through passes (0 = ask every judge)");
  s.AddInt("fusion.free_space_window_px", &f.free_space_window_px, Affects("px", Closed(0, 8), kSac),
           "free space: a view sees through a point only if every depth within this many pixels of it does");
  s.AddInt("fusion.free_space_edge_band_px", &f.free_space_edge_band_px,
           Affects("px", Closed(0, kDepthEdgeReachPx), kSac),
           "free space: points this close to a foreground edge of their own view are judged by the pixel alone");
  s.AddDouble("fusion.depth_edge_jump_gsd", &f.depth_edge_jump_gsd, Affects("GSD", Above(0), kSac),
              "free space: a depth jump of more than this many local GSDs is a foreground edge");
  s.AddInt("fusion.min_consistent_views", &f.min_consistent_views, Affects("views", Closed(1, 64), kSac),
           "outliers: min views (own included) agreeing with a point");
  s.AddDouble("fusion.outlier_expected_factor", &f.outlier_expected_factor, Affects("-", AtLeast(0), kSac),
              "outliers: with estimated noise, ask at most 1 + this x the expected agreeing views (0 = off)");
  s.AddInt("fusion.weak_support_min_views", &f.weak_support_min_views, Affects("views", Closed(0, 64), kSac),
           "outliers: views (own included) a point needs where a view that could see it (not occluded) has no depth "
           "there; at most 1 + the views that could see it (0 = off; 3 for raw single-pair stereo depth maps)");
  s.AddInt("fusion.weak_support_rim_px", &f.weak_support_rim_px, Affects("px", Closed(0, kDepthEdgeReachPx), kSac),
           "weak support: a pixel this close to a hole of its own depth map needs weak_support_min_views agreeing "
           "views even where fewer could see it (0 = off; no effect while weak_support_min_views is 0)");
  s.AddBool("fusion.independent_support", &f.independent_support, Affects("-", {}, kSac),
            "outliers: where the input names each view's stereo partners (patch-match.cfg), the agreeing views that "
            "are not partners of a point's view must be at least as many as those that could see it but have no depth "
            "there (false = off)");
  s.AddDouble("fusion.correspondence_tolerance_sigmas", &f.correspondence_tolerance_sigmas,
              Affects("sigma", AtLeast(0), kSac),
              "reprojection correspondences: also agree within this many sigmas of estimated noise (0 = off)");
  s.AddDouble("fusion.coverage_tolerance_sigmas", &f.coverage_tolerance_sigmas, Affects("sigma", AtLeast(0), kSac),
              "collapse coverage: also agree within this many sigmas of estimated noise (0 = off)");
  s.AddString("fusion.combine", &f.combine, Affects("-", Choices({"average", "select"}), kSac),
              "emitted depth: average (selected pixel, depth averaged over agreeing views) | select (as selected)");
  s.AddDouble("fusion.combine_gate_gsd", &f.combine_gate_gsd, Affects("GSD", Above(0), kSac),
              "average: agreement gate along the ray, local GSDs");
  s.AddDouble("fusion.combine_gate_sigmas", &f.combine_gate_sigmas, Affects("sigma", AtLeast(0), kSac),
              "average: ... or this many sigmas of the own depth's estimated noise");
  s.AddDouble("fusion.combine_slope_step_sigmas", &f.combine_slope_step_sigmas, Affects("sigma", AtLeast(0), kSac),
              "average: ray-surface slope over max(1 GSD, this many sigmas of the own depth's noise)");
  s.AddString("fusion.combine_weights", &f.combine_weights, Affects("-", Choices({"view", "equal", "noise"}), kSac),
              "average: view (1/k^2 of the estimated per-view noise) | equal | noise (k z^2/f and slope)");
  s.AddString("fusion.combine_surface", &f.combine_surface, Affects("-", Choices({"plane", "secant"}), kSac),
              "average: neighbour surface on the ray along the superpixel's plane (views within 30 deg) | by a secant");
  s.AddInt("fusion.combine_passes", &f.combine_passes, Affects("passes", Closed(1, 4), kSac),
           "average: passes of the mean, each from the previous mean");
  s.AddDouble("fusion.combine_later_pass_gate", &f.combine_later_pass_gate, Affects("-", Closed(0.05, 1), kSac),
              "average: later passes' gate around the previous mean, x the gate (1 = all of it)");
  s.AddDouble("fusion.combine_later_pass_min_shift_gsd", &f.combine_later_pass_min_shift_gsd,
              Affects("GSD", AtLeast(0), kSac),
              "average: a later pass only where the previous one moved the centre at least this far (0 = always)");
  s.AddBool("fusion.combine_anchors", &f.combine_anchors, Affects("-", {}, kSac),
            "average: combine the anchors exactly, interpolate between them where smooth (false = every pixel)");
  s.AddInt("fusion.combine_max_views", &f.combine_max_views, Affects("views", Closed(1, 64), kSac),
           "average: views consulted per view");
  s.AddDouble("fusion.combine_max_view_angle_deg", &f.combine_max_view_angle_deg, Affects("deg", Closed(0, 180), kSac),
              "average: max angle between those views' directions, deg");
  s.AddDouble("fusion.combine_region_m", &f.combine_region_m, Affects("m", Closed(0, 1e6), kSac),
              "average: side of the square regions the consulted views are chosen for (0 = one per view)");
  s.AddString("fusion.superpixel_cache_dir", &c->fusion.superpixel_cache_dir, Neutral("-", AnyText()),
              "where superpixels are stored and reused; empty = <output.dir>/superpixels");
  SuperpixelOptions& sp = f.superpixels;
  s.AddInt("superpixels.region_size_px", &sp.region_size_px, Affects("px", Closed(2, 128), kSac),
           "SLIC region size, depth-map pixels");
  s.AddFloat("superpixels.ruler", &sp.ruler, Affects("-", Above(0), kSac), "SLIC compactness");
  s.AddInt("superpixels.iterations", &sp.iterations, Affects("-", Closed(1, 100), kSac), "SLIC iterations");
  s.AddString("superpixels.algorithm", &sp.algorithm,
              Affects("-", Choices({"fast", "slic", "slico", "mslic", "pixels"}), kSac),
              "fast (our SLIC) | slic | slico | mslic (OpenCV) | pixels (one node per pixel, ablation)");
  s.AddInt("superpixels.block_size_px", &sp.block_size_px, Affects("px", AnyNumber(), kSac),
           "images are segmented in blocks of this size, px");
  s.AddFloat("superpixels.depth_weight", &sp.depth_weight, Affects("Lab/m", AtLeast(0), kSac),
             "weight of depth as an extra SLIC channel (0 = off)");
  ConsistencyOptions& cons = c->fusion.consistency;  // method consistency
  s.AddDouble("consistency.depth_threshold_rel", &cons.depth_threshold_rel,
              Affects("-", OpenClosed(0, 0.5), kConsistency),
              "redundant / occluded when the reprojected depth is within / in front by this fraction of the "
              "neighbour's depth (paper: 0.01); (0, 0.5]");
  DisparityNormalOptions& dn = c->fusion.disparity_normal;  // method disparity_normal
  s.AddDouble("disparity_normal.disparity_threshold_px", &dn.disparity_threshold_px,
              Affects("px", Above(0), kDisparityNormal),
              "max disparity difference f b |1/z - 1/d|, pixels (fusibile: 0.5); > 0");
  s.AddDouble("disparity_normal.normal_threshold_deg", &dn.normal_threshold_deg,
              Affects("deg", OpenClosed(0, 180), kDisparityNormal),
              "max angle between normals, degrees (paper: 30); (0, 180]");
  s.AddInt("disparity_normal.min_consistent_views", &dn.min_consistent_views,
           Affects("views", Closed(1, 64), kDisparityNormal),
           "consistent neighbour views needed to keep a point (paper: 2); 1-64");
  s.AddInt("disparity_normal.normal_radius_px", &dn.normal_radius_px, Affects("px", Closed(1, 10), kDisparityNormal),
           "normals are plane fits to the depth in (2r+1)^2 pixels; r in 1-10");
  TsdfOptions& ts = c->fusion.tsdf;  // method tsdf
  s.AddDouble("tsdf.voxel_size_gsd", &ts.voxel_size_gsd, Affects("GSD", Above(0), kTsdf),
              "voxel edge, in GSDs of the block (median over views of the principal ray's depth at the median "
              "sparse-point height / focal); > 0");
  s.AddDouble("tsdf.truncation_gsd", &ts.truncation_gsd, Affects("GSD", AnyNumber(), kTsdf),
              "truncation distance, GSDs; > tsdf.voxel_size_gsd");
  s.AddDouble("tsdf.min_weight", &ts.min_weight, Affects("-", AtLeast(1), kTsdf),
              "observations both voxels of a zero crossing need; >= 1");
  s.AddDouble("tsdf.max_memory_gb", &ts.max_memory_gb, Affects("GiB", AtLeast(0), kTsdf),
              "voxel grid limit per run or tile, GiB; 0 = resources.memory_gb; >= 0");
  MultirayOptions& mr = c->fusion.multiray;  // method multiray
  s.AddDouble("multiray.depth_tolerance_gsd", &mr.depth_tolerance_gsd, Affects("GSD", Above(0), kMultiray),
              "a neighbour pixel joins a group when its depth agrees within this many local GSDs; > 0");
  s.AddInt("multiray.min_rays", &mr.min_rays, Affects("rays", Closed(2, 65), kMultiray),
           "rays a group needs to be triangulated; 2-65");
  s.AddDouble("multiray.ray_sigma_px", &mr.ray_sigma_px, Affects("px", Above(0), kMultiray),
              "precision across a ray, pixels; > 0");
  s.AddDouble("multiray.depth_sigma_gsd", &mr.depth_sigma_gsd, Affects("GSD", AtLeast(0), kMultiray),
              "precision of a member's depth along its ray, local GSDs; 0 = rays only (pure intersection)");
  TilingOptions& t = c->tiling;
  s.AddDouble(
      "tiling.tile_size_m", &t.tile_size_m, Affects("m", AtLeast(0)),
      "geo-tile edge, metres; 0 = automatic: untiled when the block fits in resources.memory_gb, else the largest "
      "tiles that fit; >= 0");
  s.AddDouble("tiling.halo_m", &t.halo_m, Affects("m", AtLeast(0)), "halo around each tile core, metres; >= 0");
  s.AddInt("tiling.window_margin_px", &t.window_margin_px, Affects("px", AtLeast(0)),
           "padding of each view's depth window, depth pixels");
  s.AddDouble("tiling.z_min_m", &t.z_min_m, Affects("m", AnyNumber()),
              "block height range, metres; only used when the sparse model has no points");
  s.AddDouble("tiling.z_max_m", &t.z_max_m, Affects("m", AnyNumber()), "block height range, metres; > tiling.z_min_m");
  s.AddDouble("tiling.claim_timeout_s", &t.claim_timeout_s, Neutral("s", Above(0)),
              "multi-worker runs: a tile claim older than this is stale and taken over, seconds; > 0");
  s.AddInt("resources.threads", &c->resources.threads, Neutral("threads", AtLeast(0)), "worker threads; 0 = all cores");
  s.AddDouble("resources.memory_gb", &c->resources.memory_gb, Neutral("GiB", Above(0)), "memory budget, GiB; > 0");
  s.AddString("evaluation.reference", &c->evaluation.reference, Neutral("-", AnyText()),
              "reference LAS to score the result against; empty = no scoring");
  s.AddString("evaluation.mask", &c->evaluation.mask, Neutral("-", AnyText()),
              "evaluation mask PNG with JSON sidecar; empty = none");
  s.AddDouble("evaluation.gsd_m", &c->evaluation.gsd_m, Neutral("m", Above(0)),
              "ground sampling distance, metres; > 0");
  s.AddDoubleList("evaluation.tau_gsd", &c->evaluation.tau_gsd, Neutral("GSD", Required(Above(0))),
                  "F1 distance thresholds in GSD units; each > 0");
  s.AddBool("evaluation.align", &c->evaluation.align, Neutral("-", {}),
            "robust ICP of the result onto the reference first");
  s.AddString("log.level", &c->log.level, Neutral("-", Choices({"trace", "debug", "info", "warn", "error"})),
              "log level: trace | debug | info | warn | error");
  return s;
}

std::vector<OptionRow> JobOptionRows(const JobConfig& config) {
  JobConfig copy = config;
  return MakeOptionTable(&copy).Rows();
}

}  // namespace sacfuse
