#pragma once
// The options of one `sacfuse run`, as plain structs with defaults and units. The YAML keys are the struct paths
// (e.g. `output.scale_m`); config/option_table.cc binds each key to its field, unit, range, documentation and
// result flag, so the parser, the validator, `--print-defaults` and the resume hash share one source of truth.
#include <string>
#include <utility>
#include <vector>

#include "config/config_override.h"
#include "config/fusion_method_kind.h"
#include "core/consistency_fusion.h"
#include "core/coregistration.h"
#include "core/disparity_normal_fusion.h"
#include "core/multiray_fusion.h"
#include "core/sac_options.h"
#include "core/tsdf_fusion.h"
#include "tiling/tile_grid.h"

namespace sacfuse {

struct InputOptions {
  std::string format = "colmap";        // input kind: colmap (a COLMAP dense workspace)
                                        //   | openmvs (a folder of OpenMVS depth%04u.dmap files)
                                        //   | rasters (float32 TIFF depth rasters + a camera file)
  std::string path;                     // workspace folder; relative paths are relative to the config file
  std::string depth_type = "geometric";  // which COLMAP depth maps: geometric | photometric
  // format rasters (io/raster_block.h): the camera file (.yaml/.yml/.csv); relative paths are relative to the
  // config file; "" = the cameras.yaml, cameras.yml or cameras.csv in `path`.
  std::string cameras;
  std::string depth_kind = "z";         // format rasters: z (along the optical axis) | range (along the ray), metres
  // The input's coordinates are project-CRS coordinates minus this point (east, north, height; metres): a
  // workspace shifted to a round local origin (COLMAP computes in float32). World = input + origin_m, in doubles.
  // Applies to COLMAP and OpenMVS poses and to camera-file x_m/y_m/z_m (in input.cameras_crs when set).
  std::vector<double> origin_m = {0.0, 0.0, 0.0};
  // format rasters: the CRS of the camera file's positions (io/crs.h; x_m/y_m/z_m, or the datum of lat/lon/h);
  // "" = the project CRS. Positions are transformed into `crs` through PROJ (io/camera_placement.h).
  std::string cameras_crs;
};

struct OutputOptions {
  std::string dir = "sacfuse_out";      // output folder (fused.laz or fused.las, logs, effective config, run report)
  std::string format = "laz";           // laz (LASzip-compressed, io/laz_*.h) | las (uncompressed): DIR/fused.<format>
                                        // | copc (io/copc_writer.h): DIR/fused.copc.laz
  std::string las_version = "1.4";      // 1.4 (point format 7) | 1.2 (point format 3)
  double scale_m = 0.001;               // LAS coordinate quantum, metres (10^k x {1, 0.5, 0.25})
  // The DSM raster product (docs/dsm-and-ortho.md; jobs/dsm_product.h): DIR/dsm.tif, a float32 Cloud Optimized
  // GeoTIFF, or DIR/dsm.vrt over DIR/dsm/*.tif for extents too large for one file (raster_layout).
  std::string dsm = "auto";             // auto (on when `crs` is set) | on | off
  double dsm_cell_m = 0.0;              // cell edge, metres; 0 = automatic (2 x the block's GSD, rounded)
  double dsm_max_hole_m = 2.0;          // holes up to this size (m, each side) are filled from their rim
  std::string raster_layout = "auto";   // auto | single (one COG) | tiles (COG blocks + a VRT)
  // The true orthophoto on the DSM's cells (docs/dsm-and-ortho.md; jobs/ortho_product.h): DIR/ortho.tif, an RGBA
  // 8-bit Cloud Optimized GeoTIFF (or DIR/ortho.vrt over DIR/ortho/*.tif, as the DSM's raster_layout).
  std::string ortho = "auto";           // auto (on when the run writes the DSM) | on | off
};

struct FusionOptions {
  // sac:   Select-and-Combine (Netlets over superpixels; see core/sac_options.h for every option).
  // union: every valid depth pixel becomes a point (no fusion; the "before fusion" baseline).
  // consistency | disparity_normal | tsdf | multiray: the paper's comparison methods [15] [13] [7] [35]
  //   (core/consistency_fusion.h, disparity_normal_fusion.h, tsdf_fusion.h, multiray_fusion.h); they reproject
  //   into the views fusion.max_neighbor_views / max_view_angle_deg / min_footprint_overlap choose.
  // Parsed once into the enum (config/fusion_method_kind.h); NameOf(method) is its YAML name.
  FusionMethodKind method = FusionMethodKind::kSac;
  SacOptions sac;          // YAML: fusion.<field> and superpixels.<field>
  ConsistencyOptions consistency;          // YAML: consistency.<field>
  DisparityNormalOptions disparity_normal; // YAML: disparity_normal.<field>
  TsdfOptions tsdf;                        // YAML: tsdf.<field>
  MultirayOptions multiray;                // YAML: multiray.<field>
  std::string superpixel_cache_dir;  // "" = <output.dir>/superpixels; reused by later runs with equal options
};

struct ResourceOptions {
  int threads = 0;          // worker threads; 0 = all cores
  double memory_gb = 4.0;   // memory budget, GiB
};

struct EvaluationOptions {
  std::string reference;                   // reference LAS; when set, the run scores its result ("" = no scoring)
  std::string mask;                        // evaluation mask PNG (+ JSON sidecar); "" = whole reference
  double gsd_m = 0.10;                     // ground sampling distance, metres (thresholds are multiples of it)
  std::vector<double> tau_gsd = {2.0, 5.0};  // F1 thresholds in GSD units
  bool align = false;                      // robust ICP onto the reference before scoring
};

struct LogOptions {
  std::string level = "info";   // trace | debug | info | warn | error
};

struct JobConfig {
  // Project CRS of the world coordinates (io/crs.h, through PROJ): "" = not georeferenced (local metres, no CRS in
  // the LAS), any metric projected CRS PROJ knows ("EPSG:25832"), a compound one with orthometric heights
  // ("EPSG:2154+5720"), WKT1/WKT2/PROJJSON, or "ENU:lat,lon,h" (local east-north-up frame at that origin).
  std::string crs;
  InputOptions input;
  OutputOptions output;
  CoregistrationOptions coregistration;  // YAML: coregistration.<field>; every method (core/coregistration.h)
  FusionOptions fusion;
  TilingOptions tiling;    // YAML: tiling.<field>; tile_size_m = 0 runs untiled
  ResourceOptions resources;
  EvaluationOptions evaluation;
  LogOptions log;
  std::string source_file;  // the YAML file this came from ("" for defaults)
  std::vector<ConfigOverride> overrides;  // the keys the command line set on top of it, in order
};

// Whether the run writes the DSM: output.dsm on, or auto with a project CRS (a run in a CRS-less local frame, e.g.
// an SfM reconstruction whose z need not point up, gets no DSM unless asked for).
bool DsmWanted(const JobConfig& config);
// Whether the run writes the true orthophoto: output.ortho auto or on, and the run writes the DSM (the ortho is made
// on the DSM's cells and tested for occlusion against it; `on` without a DSM is a config error).
bool OrthoWanted(const JobConfig& config);

// Reads, type-checks and validates a YAML config, with `overrides` (the command line's --set ...) applied on top
// before validation. Unknown keys, wrong types and out-of-range values throw ConfigError naming the file, line (or
// option), key, value and rule (all problems at once). Relative paths are resolved against the config file's
// folder, those of overrides against the current directory.
JobConfig LoadJobConfig(const std::string& path, const std::vector<ConfigOverride>& overrides = {});
// Parses YAML text (for tests); `source_name` appears in messages. Paths are resolved against `base_dir`.
JobConfig ParseJobConfig(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir,
                         const std::vector<ConfigOverride>& overrides = {});
// Validation of values alone (after parsing or for configs built in code).
void ValidateJobConfig(const JobConfig& config);
// The config as YAML. With comments: a header naming the sacfuse version, the source file and the overrides, and
// every key documented with its unit and rule (--print-defaults, sacfuse.effective.yaml).
std::string DumpJobConfig(const JobConfig& config, bool with_comments);
// Every key of the config with its value as YAML text ("fusion.tau_m" -> "2"), in schema order.
std::vector<std::pair<std::string, std::string>> JobConfigValues(const JobConfig& config);

}  // namespace sacfuse
