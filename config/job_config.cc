#include "config/job_config.h"

#include <filesystem>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "config/config_schema.h"
#include "core/crs.h"
#include "core/option_check.h"
#include "core/error.h"
#include "io/input_file.h"

namespace sacfuse {
namespace {

// The single place where YAML keys meet struct fields. Docs name the unit and the rule.
ConfigSchema MakeSchema(JobConfig* c) {
  ConfigSchema s;
  s.AddString("crs", &c->crs,
              "project CRS of the coordinates, written into every LAS: \"\" = none (local metres) | EPSG:326zz / "
              "EPSG:327zz (WGS 84 / UTM zone zz N / S) | EPSG:258zz (ETRS89 / UTM zone zz N, zz = 28..38) | "
              "ENU:lat,lon,h (local east-north-up frame at that origin; degrees, metres)");
  s.AddString("input.format", &c->input.format,
              "input kind: colmap (a COLMAP dense workspace) | openmvs (a folder of OpenMVS depth%04u.dmap files) "
              "| rasters (float32 TIFF depth rasters + a camera file, see input.cameras)",
              {"colmap", "openmvs", "rasters"});
  s.AddString("input.path", &c->input.path, "input folder (relative to this file); required");
  s.AddString("input.depth_type", &c->input.depth_type, "COLMAP depth maps to fuse: geometric | photometric",
              {"geometric", "photometric"});
  s.AddString("input.cameras", &c->input.cameras,
              "rasters: camera file (.yaml/.yml/.csv, relative to this file); empty = cameras.yaml, cameras.yml or "
              "cameras.csv in input.path");
  s.AddString("input.depth_kind", &c->input.depth_kind,
              "rasters: depth values are z (along the optical axis) | range (distance along the pixel's ray), metres",
              {"z", "range"});
  s.AddString("output.dir", &c->output.dir, "output folder (relative to this file)");
  s.AddString("output.format", &c->output.format,
              "point cloud format of DIR/fused.<format>: laz (LASzip-compressed, 50,000-point chunks) | las "
              "(uncompressed); tile files stay uncompressed LAS (intermediate, read back by merge and report)",
              {"laz", "las"});
  s.AddString("output.las_version", &c->output.las_version, "LAS version: 1.4 (point format 7) | 1.2 (format 3)",
              {"1.4", "1.2"});
  s.AddDouble("output.scale_m", &c->output.scale_m, "LAS coordinate quantum, metres; 10^k x {1, 0.5, 0.25}");
  s.AddString("fusion.method", &c->fusion.method,
              "fusion method: sac (Select-and-Combine) | union (every valid depth pixel: the 'before fusion' baseline) "
              "| the paper's comparison methods: consistency ([15]: occluded and redundant depths removed) | "
              "disparity_normal ([13]: disparity + normal consistency, averaged) | tsdf ([7]: truncated signed "
              "distance on a sparse voxel grid) | multiray ([35]: correspondence groups triangulated from all rays)",
              {"sac", "union", "consistency", "disparity_normal", "tsdf", "multiray"});
  SacOptions& f = c->fusion.sac;
  s.AddInt("fusion.max_neighbor_views", &f.max_neighbor_views, "neighbour views per view (by footprint overlap)");
  s.AddDouble("fusion.max_view_angle_deg", &f.max_view_angle_deg, "max angle between neighbours' view directions, deg");
  s.AddDouble("fusion.min_footprint_overlap", &f.min_footprint_overlap, "min shared fraction of a footprint, 0-1");
  s.AddString("fusion.correspondence", &f.correspondence,
              "point groups: reprojection | proximity (3D radius) | dense (input's dense matches)",
              {"reprojection", "proximity", "dense"});
  s.AddDouble("fusion.depth_tolerance_gsd", &f.depth_tolerance_gsd, "depth agreement tolerance, in local GSDs");
  s.AddDouble("fusion.depth_tolerance_rel", &f.depth_tolerance_rel, "plus this fraction of the depth, 0-0.5");
  s.AddDouble("fusion.proximity_radius_m", &f.proximity_radius_m, "proximity search radius, m; 0 = 1.5 superpixels");
  s.AddDouble("fusion.tau_m", &f.tau_m, "Netlet edge threshold tau, metres (paper: 2)");
  s.AddString("fusion.netlets", &f.netlets, "Netlets: node (one per node, Algorithm 1) | partition (disjoint)",
              {"node", "partition"});
  s.AddString("fusion.unary", &f.unary, "unary term: quality | paper (constant)", {"quality", "paper"});
  s.AddDouble("fusion.quality_weight", &f.quality_weight, "quality unary: weight of relative stereo depth uncertainty (z^2/f)");
  s.AddDouble("fusion.min_incidence_cos", &f.min_incidence_cos, "quality unary: floor of cos(incidence), 0.01-1");
  s.AddDouble("fusion.agreement_weight", &f.agreement_weight, "quality unary: weight of disagreement");
  s.AddDouble("fusion.agreement_tolerance_gsd", &f.agreement_tolerance_gsd,
              "quality unary: stricter 'views agree' tolerance, local GSDs");
  s.AddDouble("fusion.displacement_weight", &f.displacement_weight, "quality unary: weight of node displacement");
  s.AddDouble("fusion.smoothness_weight", &f.smoothness_weight, "smoothness between adjacent clusters (0 = off)");
  s.AddInt("fusion.smoothness_rounds", &f.smoothness_rounds, "rounds of that smoothness");
  s.AddString("fusion.collapse", &f.collapse,
              "collapse: netlet (drop pixels the Netlet's chosen view emits) | best_view (also those a more precise "
              "view holds)",
              {"netlet", "best_view"});
  s.AddDouble("fusion.redundancy_tolerance_sigmas", &f.redundancy_tolerance_sigmas,
              "best_view: 'same surface' also within this many sigmas of estimated noise (0 = strict tolerance)");
  s.AddInt("fusion.free_space_min_views", &f.free_space_min_views,
           "free space: drop points that at least this many views see through (0 = off)");
  s.AddDouble("fusion.free_space_sigmas", &f.free_space_sigmas,
              "free space: 'sees through' beyond this many sigmas of the estimated noise");
  s.AddInt("fusion.min_consistent_views", &f.min_consistent_views,
           "outliers: min views (own included) agreeing with a point");
  s.AddDouble("fusion.outlier_expected_factor", &f.outlier_expected_factor,
              "outliers: with estimated noise, ask at most 1 + this x the expected agreeing views (0 = off)");
  s.AddDouble("fusion.correspondence_tolerance_sigmas", &f.correspondence_tolerance_sigmas,
              "reprojection correspondences: also agree within this many sigmas of estimated noise (0 = off)");
  s.AddDouble("fusion.coverage_tolerance_sigmas", &f.coverage_tolerance_sigmas,
              "collapse coverage: also agree within this many sigmas of estimated noise (0 = off)");
  s.AddString("fusion.combine", &f.combine,
              "emitted depth: average (selected pixel, depth averaged over agreeing views) | select (as selected)",
              {"average", "select"});
  s.AddDouble("fusion.combine_gate_gsd", &f.combine_gate_gsd, "average: agreement gate along the ray, local GSDs");
  s.AddDouble("fusion.combine_gate_sigmas", &f.combine_gate_sigmas,
              "average: ... or this many sigmas of the own depth's estimated noise");
  s.AddInt("fusion.combine_max_views", &f.combine_max_views, "average: views consulted per view");
  s.AddDouble("fusion.combine_max_view_angle_deg", &f.combine_max_view_angle_deg,
              "average: max angle between those views' directions, deg");
  s.AddString("fusion.superpixel_cache_dir", &c->fusion.superpixel_cache_dir,
              "where superpixels are stored and reused; empty = <output.dir>/superpixels");
  SuperpixelOptions& sp = f.superpixels;
  s.AddInt("superpixels.region_size_px", &sp.region_size_px, "SLIC region size, depth-map pixels");
  s.AddFloat("superpixels.ruler", &sp.ruler, "SLIC compactness");
  s.AddInt("superpixels.iterations", &sp.iterations, "SLIC iterations");
  s.AddString("superpixels.algorithm", &sp.algorithm,
              "fast (our SLIC) | slic | slico | mslic (OpenCV) | pixels (one node per pixel, ablation)",
              {"fast", "slic", "slico", "mslic", "pixels"});
  s.AddInt("superpixels.block_size_px", &sp.block_size_px, "images are segmented in blocks of this size, px");
  s.AddFloat("superpixels.depth_weight", &sp.depth_weight, "weight of depth as an extra SLIC channel (0 = off)");
  ConsistencyOptions& cons = c->fusion.consistency;  // method consistency
  s.AddDouble("consistency.depth_threshold_rel", &cons.depth_threshold_rel,
              "redundant / occluded when the reprojected depth is within / in front by this fraction of the "
              "neighbour's depth (paper: 0.01); (0, 0.5]");
  DisparityNormalOptions& dn = c->fusion.disparity_normal;  // method disparity_normal
  s.AddDouble("disparity_normal.disparity_threshold_px", &dn.disparity_threshold_px,
              "max disparity difference f b |1/z - 1/d|, pixels (fusibile: 0.5); > 0");
  s.AddDouble("disparity_normal.normal_threshold_deg", &dn.normal_threshold_deg,
              "max angle between normals, degrees (paper: 30); (0, 180]");
  s.AddInt("disparity_normal.min_consistent_views", &dn.min_consistent_views,
           "consistent neighbour views needed to keep a point (paper: 2); 1-64");
  s.AddInt("disparity_normal.normal_radius_px", &dn.normal_radius_px,
           "normals are plane fits to the depth in (2r+1)^2 pixels; r in 1-10");
  TsdfOptions& ts = c->fusion.tsdf;  // method tsdf
  s.AddDouble("tsdf.voxel_size_gsd", &ts.voxel_size_gsd,
              "voxel edge, in GSDs of the block (median over views of the principal ray's depth at the median "
              "sparse-point height / focal); > 0");
  s.AddDouble("tsdf.truncation_gsd", &ts.truncation_gsd, "truncation distance, GSDs; > tsdf.voxel_size_gsd");
  s.AddDouble("tsdf.min_weight", &ts.min_weight, "observations both voxels of a zero crossing need; >= 1");
  s.AddDouble("tsdf.max_memory_gb", &ts.max_memory_gb,
              "voxel grid limit per run or tile, GiB; 0 = resources.memory_gb; >= 0");
  MultirayOptions& mr = c->fusion.multiray;  // method multiray
  s.AddDouble("multiray.depth_tolerance_gsd", &mr.depth_tolerance_gsd,
              "a neighbour pixel joins a group when its depth agrees within this many local GSDs; > 0");
  s.AddInt("multiray.min_rays", &mr.min_rays, "rays a group needs to be triangulated; 2-65");
  s.AddDouble("multiray.ray_sigma_px", &mr.ray_sigma_px, "precision across a ray, pixels; > 0");
  s.AddDouble("multiray.depth_sigma_gsd", &mr.depth_sigma_gsd,
              "precision of a member's depth along its ray, local GSDs; 0 = rays only (pure intersection)");
  TilingOptions& t = c->tiling;
  s.AddDouble("tiling.tile_size_m", &t.tile_size_m,
              "geo-tile edge, metres; 0 = automatic: untiled when the block fits in resources.memory_gb, else the largest "
              "tiles that fit; >= 0");
  s.AddDouble("tiling.halo_m", &t.halo_m, "halo around each tile core, metres; >= 0");
  s.AddInt("tiling.window_margin_px", &t.window_margin_px, "padding of each view's depth window, depth pixels");
  s.AddDouble("tiling.z_min_m", &t.z_min_m,
              "block height range, metres; only used when the sparse model has no points");
  s.AddDouble("tiling.z_max_m", &t.z_max_m, "block height range, metres; > tiling.z_min_m");
  s.AddDouble("tiling.claim_timeout_s", &t.claim_timeout_s,
              "multi-worker runs: a tile claim older than this is stale and taken over, seconds; > 0");
  s.AddInt("resources.threads", &c->resources.threads, "worker threads; 0 = all cores");
  s.AddDouble("resources.memory_gb", &c->resources.memory_gb, "memory budget, GiB; > 0");
  s.AddString("evaluation.reference", &c->evaluation.reference,
              "reference LAS to score the result against; empty = no scoring");
  s.AddString("evaluation.mask", &c->evaluation.mask, "evaluation mask PNG with JSON sidecar; empty = none");
  s.AddDouble("evaluation.gsd_m", &c->evaluation.gsd_m, "ground sampling distance, metres; > 0");
  s.AddDoubleList("evaluation.tau_gsd", &c->evaluation.tau_gsd, "F1 distance thresholds in GSD units; each > 0");
  s.AddBool("evaluation.align", &c->evaluation.align, "robust ICP of the result onto the reference first");
  s.AddString("log.level", &c->log.level, "log level: trace | debug | info | warn | error",
              {"trace", "debug", "info", "warn", "error"});
  return s;
}

std::string ResolvePath(const std::string& path, const std::string& base_dir) {
  if (path.empty() || base_dir.empty()) return path;
  std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

// Prefixes each message line that starts with a key present in the YAML with "<source>:<line>: ", so range errors
// found after parsing point at the line like type errors do.
std::string AnnotateWithLines(const std::string& message, const std::map<std::string, int>& key_lines,
                              const std::string& source) {
  std::istringstream in(message);
  std::string line, out;
  while (std::getline(in, line)) {
    const size_t start = line.find_first_not_of(' ');
    if (start != std::string::npos) {
      const size_t end = line.find_first_of(" [", start);
      const std::string key = line.substr(start, end == std::string::npos ? std::string::npos : end - start);
      if (const auto it = key_lines.find(key); it != key_lines.end()) {
        line = line.substr(0, start) + source + ":" + std::to_string(it->second) + ": " + line.substr(start);
      }
    }
    out += (out.empty() ? "" : "\n") + line;
  }
  return out;
}

bool IsAllowedLasScale(double scale) {
  if (!(scale > 0)) return false;
  for (double mantissa : {1.0, 0.5, 0.25}) {
    const double k = std::log10(scale / mantissa);
    if (std::abs(k - std::round(k)) < 1e-9) return true;
  }
  return false;
}

// input.cameras and input.depth_kind belong to format rasters.
void CheckRasterInputKeys(const InputOptions& in, OptionChecker* check) {
  if (in.format != "rasters") {
    check->Require(in.cameras.empty(), "input.cameras", in.cameras, "only read by input.format: rasters");
    check->Require(in.depth_kind == "z", "input.depth_kind", in.depth_kind, "only read by input.format: rasters");
    return;
  }
  if (in.cameras.empty()) return;
  std::string ext = std::filesystem::path(in.cameras).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  check->Require(ext == ".yaml" || ext == ".yml" || ext == ".csv", "input.cameras", in.cameras,
                 "must be a .yaml, .yml or .csv camera file");
}

}  // namespace

void ValidateJobConfig(const JobConfig& c) {
  OptionChecker check;
  try {
    ParseProjectCrs(c.crs);
  } catch (const Error& e) {
    std::string why = e.what();
    const std::string prefix = "crs \"" + c.crs + "\": ";
    if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
    check.Require(false, "crs", "\"" + c.crs + "\"", why);
  }
  check.NotEmpty("input.path", c.input.path);
  CheckRasterInputKeys(c.input, &check);
  check.NotEmpty("output.dir", c.output.dir);
  check.Require(IsAllowedLasScale(c.output.scale_m), "output.scale_m", OptionChecker::ToString(c.output.scale_m),
                "must be 10^k x {1, 0.5, 0.25} (e.g. 0.001, 0.0025, 0.01)");
  check.InRange("output.scale_m", c.output.scale_m, 1e-6, 1.0);
  check.AtLeast("resources.threads", c.resources.threads, 0);
  check.Greater("resources.memory_gb", c.resources.memory_gb, 0.0);
  check.Greater("evaluation.gsd_m", c.evaluation.gsd_m, 0.0);
  check.Require(!c.evaluation.tau_gsd.empty(), "evaluation.tau_gsd", "[]", "must list at least one threshold");
  for (double t : c.evaluation.tau_gsd) check.Greater("evaluation.tau_gsd[]", t, 0.0);
  if (c.fusion.method == "sac") check.Absorb([&] { ValidateSacOptions(c.fusion.sac); });
  if (c.fusion.method == "consistency") check.Absorb([&] { ValidateConsistencyOptions(c.fusion.consistency); });
  if (c.fusion.method == "disparity_normal") {
    check.Absorb([&] { ValidateDisparityNormalOptions(c.fusion.disparity_normal); });
  }
  if (c.fusion.method == "tsdf") check.Absorb([&] { ValidateTsdfOptions(c.fusion.tsdf); });
  if (c.fusion.method == "multiray") check.Absorb([&] { ValidateMultirayOptions(c.fusion.multiray); });
  if (c.fusion.method == "consistency" || c.fusion.method == "disparity_normal" || c.fusion.method == "multiray") {
    check.InRange("fusion.max_neighbor_views", c.fusion.sac.max_neighbor_views, 1, 64);
    check.InRange("fusion.max_view_angle_deg", c.fusion.sac.max_view_angle_deg, 0.0, 180.0);
    check.InRange("fusion.min_footprint_overlap", c.fusion.sac.min_footprint_overlap, 0.0, 1.0);
  }
  check.Absorb([&] { ValidateTilingOptions(c.tiling); });
  check.Require(!(c.tiling.tile_size_m > 0 && c.fusion.method == "sac" && c.fusion.sac.correspondence == "dense"),
                "fusion.correspondence", c.fusion.sac.correspondence,
                "dense is not supported by tiled runs yet (tiling.tile_size_m > 0); use reprojection or proximity");
  check.ThrowIfFailed(c.source_file.empty() ? "config" : c.source_file);
}

JobConfig ParseJobConfig(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir) {
  JobConfig config;
  config.source_file = source_name;
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  std::map<std::string, int> key_lines;
  MakeSchema(&config).Parse(root, source_name, &key_lines);
  config.input.path = ResolvePath(config.input.path, base_dir);
  config.input.cameras = ResolvePath(config.input.cameras, base_dir);
  config.output.dir = ResolvePath(config.output.dir, base_dir);
  config.evaluation.reference = ResolvePath(config.evaluation.reference, base_dir);
  config.evaluation.mask = ResolvePath(config.evaluation.mask, base_dir);
  config.fusion.superpixel_cache_dir = ResolvePath(config.fusion.superpixel_cache_dir, base_dir);
  try {
    ValidateJobConfig(config);
  } catch (const ConfigError& e) {
    throw ConfigError(AnnotateWithLines(e.what(), key_lines, source_name));
  }
  return config;
}

JobConfig LoadJobConfig(const std::string& path) {
  std::ifstream in;
  try {
    in = OpenInputStream(path, "config file");
  } catch (const InputError& e) {
    throw ConfigError(e.what());
  }
  std::stringstream text;
  text << in.rdbuf();
  const auto base = std::filesystem::absolute(path).parent_path().string();
  return ParseJobConfig(text.str(), path, base);
}

std::string DumpJobConfig(const JobConfig& config, bool with_comments) {
  JobConfig copy = config;
  std::string header;
  if (with_comments) {
    header =
        "# sacfuse run configuration. Every key is optional except input.path; the values shown are the defaults.\n"
        "# Relative paths are resolved against the folder of this file.\n";
  }
  return header + MakeSchema(&copy).Dump(with_comments);
}

std::vector<std::pair<std::string, std::string>> JobConfigValues(const JobConfig& config) {
  JobConfig copy = config;
  return MakeSchema(&copy).Values();
}

}  // namespace sacfuse
