#pragma once
// `sacfuse colmap-fusion`: COLMAP's own stereo_fusion on a sacfuse input workspace, measured and converted so it
// can be scored exactly like sacfuse's output.
//
//  1. OUT/workspace: the workspace in a local world frame (shifted_workspace.h), so COLMAP's float32 maths and
//     fused.ply keep millimetres on UTM coordinates;
//  2. `colmap stereo_fusion --workspace_path OUT/workspace --workspace_format COLMAP --input_type TYPE
//     --output_path OUT/workspace/fused.ply --StereoFusion.num_threads N --StereoFusion.cache_size GB
//     --StereoFusion.use_cache 0|1 --log_to_stderr 1` as a child process (child_process.h): wall time, peak RSS,
//     CPU; its output goes to OUT/colmap.log;
//  3. OUT/fused.las from fused.ply with the offset (and input.origin_m) added back in double (ply_to_las.h).
// Scoring is the caller's (tools/cli uses the same RunEvaluation as `sacfuse run`).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "io/las_writer.h"
#include "tools/bench/child_process.h"
#include "tools/bench/shifted_workspace.h"

namespace sacfuse {

struct ColmapFusionRequest {
  std::string workspace;                 // the COLMAP dense workspace sacfuse fuses (input.path)
  std::string out_dir;                   // everything is written below it
  std::string colmap = "colmap";         // binary: a path, or a name looked up on $PATH
  std::string input_type = "geometric";  // geometric | photometric depth maps (input.depth_type)
  int threads = 0;                       // 0 = all cores (COLMAP's -1)
  double memory_gb = 4.0;                // -> StereoFusion.cache_size (GB; only used with use_cache)
  bool use_cache = false;                // StereoFusion.use_cache: bounded memory, but single-threaded in 3.8
  LasWriterOptions las;                  // LAS version and scale as the job's output.* (offset: the shift's)
  // input.origin_m: the workspace's coordinates are the CRS's minus this; added to every point, as `sacfuse run`
  // adds it to the poses.
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
  // More StereoFusion options as (name, value), e.g. ("max_normal_error", "180") -> --StereoFusion.max_normal_error
  // 180; a name given here replaces the value above (num_threads, cache_size, use_cache).
  std::vector<std::pair<std::string, std::string>> stereo_fusion_options;
};

// "NAME=VALUE" -> (NAME, VALUE); throws ConfigError unless NAME is a plain option name (letters, digits, _) and
// VALUE is not empty.
std::pair<std::string, std::string> ParseStereoFusionOption(const std::string& text);

struct ColmapFusionResult {
  std::string colmap_path;               // the binary that ran
  std::string colmap_version;            // from `colmap -h`, e.g. "COLMAP 3.8 (Commit Unknown on Unknown without CUDA)"
  std::vector<std::string> command;      // argv of the stereo_fusion run
  ShiftedWorkspace workspace;
  ChildResult run;                       // wall time, peak RSS, CPU of stereo_fusion alone
  std::string log_path, ply_path, las_path;
  uint64_t points = 0;                   // fused points (= LAS points)
  double prepare_s = 0.0;                // writing the shifted workspace
  double convert_s = 0.0;                // fused.ply -> fused.las
};

// The binary `request.colmap` resolves to; throws ConfigError (exit code 2) with install advice when there is
// none.
std::string RequireColmapBinary(const std::string& colmap);

// Steps 1-3 above. Throws ConfigError when the binary is missing, InputError when the workspace lacks what
// stereo_fusion reads, Error (with the tail of colmap.log) when stereo_fusion fails or writes no fused.ply.
ColmapFusionResult RunColmapFusion(const ColmapFusionRequest& request);

// The argv of the stereo_fusion run for a request (exposed for tests and the report).
std::vector<std::string> StereoFusionCommand(const ColmapFusionRequest& request, const std::string& colmap_path,
                                             const std::string& workspace, const std::string& ply_path);

}  // namespace sacfuse
