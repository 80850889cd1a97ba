#pragma once
// `sacfuse bench`, part 1: what to run. The options of the command, the catalogue of blocks (the procedural city
// and one block per real LiDAR city), the simulated blocks each needs (one per error scale, the no-errors ceiling,
// the ablation block and its variants) and the rows (one fusion run each) in table order. Pure: no file is read
// except the existence checks of the LiDAR files.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config/fusion_method_kind.h"

namespace sacfuse::bench {

struct QualityBenchOptions {
  std::string out_dir;                      // everything goes below it: blocks/, rows/, bench.md, bench.json
  std::vector<std::string> blocks;          // catalogue names (city, zurich, ...); empty = DefaultBlockNames()
  std::vector<double> error_scales = {1.0, 2.5};  // `sacfuse simulate --error-scale`, one block per scale
  // Depth maps of the main blocks (`sacfuse simulate --depth`): "synthetic" (the error models) or "sgbm" (matched by
  // StereoSGBM from the rendered images). The ceiling and the ablation blocks stay synthetic.
  std::string depth = "synthetic";
  uint64_t seed = 7;                        // the same seed for every block (scene, cameras and errors)
  std::string preset = "small";             // simulate preset of every main block (procedural and LiDAR)
  std::vector<std::string> methods = FusionMethodNameList();  // every fusion.method
  std::string colmap_path;                  // resolved COLMAP binary; "" = no COLMAP rows
  bool ablations = true;
  std::string ablation_preset = "tiny";     // the procedural block of the ablation rows
  int max_ablation_rows = 0;                // 0 = every ablation row; else the first N (--quick: 2)
  std::string lidar_dir;                    // folder holding lastools/, pdal_autzen/, ...; "" = none found
  bool force = false;                       // re-run rows whose result exists
  bool keep_clouds = false;                 // keep every row's fused LAS (default: deleted once scored)
  // aerial-bench (aerial_bench_plan.h): its blocks, run beside ours; empty = off (--aerial-bench off, --quick).
  std::vector<std::string> aerial_blocks = {"montpellier", "montpellier_e25", "zurich", "zurich_e25", "stbarth",
                                            "stbarth_e25"};
  std::string aerial_bench_dir;             // the aerial-bench folder; "" = not found (its blocks are skipped)
  std::string python = "/usr/bin/python3";  // runs its scripts (Debian's numpy, scipy, opencv, open3d)
};

// The --quick preset (tests, CI): tiny preset, city only, scale 1, methods sac, union, tsdf, two ablation rows,
// no COLMAP, no aerial-bench. out_dir and lidar_dir are left as they are.
void ApplyQuickPreset(QualityBenchOptions* options);

// $SACFUSE_SHARED/<relative> when SACFUSE_SHARED is set and it exists, else <repo>/../shared/<relative> for the
// source tree this was built from; "" when neither folder exists.
std::string DefaultSharedFolder(const std::string& relative);
// DefaultSharedFolder("research-data/lidar").
std::string DefaultLidarDir();

// One entry of the block catalogue: a LiDAR city and the crop that makes a block of about the small preset's size.
struct LidarCity {
  const char* name;
  const char* file;      // relative to the LiDAR folder; .las or .laz
  double area_m;         // `simulate --area` (centred square crop), metres; 0 = the preset's area (or the file)
  bool in_default;       // part of the default --blocks (false: reference too sparse to score 2 x GSD)
  const char* note;      // what the file is
};
const std::vector<LidarCity>& LidarCatalogue();
// Every name --blocks accepts: "city" then the LiDAR cities.
std::vector<std::string> BlockNames();
// The blocks run when --blocks is not given: "city" and the LiDAR cities marked in_default.
std::vector<std::string> DefaultBlockNames();

// One `sacfuse simulate` run. `id` is its folder name under OUT/blocks and encodes every argument, so blocks with
// equal arguments are simulated once and shared by rows.
struct BlockSpec {
  std::string id;
  std::string scene;              // catalogue name: city, zurich, ...
  std::string preset;
  std::string from_las;           // "" = the procedural city
  double area_m = 0.0;            // 0 = the preset's
  uint64_t seed = 7;
  double error_scale = 1.0;
  bool no_errors = false;         // the ceiling: perfect depth, true poses
  bool no_pose_errors = false;    // true poses, every other error
  bool consistency_graphs = false;  // pass --consistency-graphs (dense correspondences)
  bool normal_maps = true;        // false: --no-normal-maps (only COLMAP reads them)
  std::string depth = "synthetic";  // simulate --depth (sgbm: matched depth maps)
  // Arguments after `sacfuse`: simulate --preset ... --out <block_dir>.
  std::vector<std::string> SimulateArgs(const std::string& block_dir) const;
};

enum class RowKind { kSacfuse, kColmap };

// One row of the tables: a fusion of one block, scored against the block's reference.
struct RowSpec {
  std::string section;           // "main" or "ablation"
  std::string scene;             // catalogue name of the block (table group)
  double error_scale = 1.0;      // table group of the main section
  std::string name;              // the row's label: sac, union, ..., COLMAP ..., ceiling ...
  std::string block_id;          // BlockSpec::id it runs on
  RowKind kind = RowKind::kSacfuse;
  std::vector<std::pair<std::string, std::string>> overrides;  // YAML key (dotted) -> value, on the block config
  std::vector<std::string> stereo_fusion;  // COLMAP rows: NAME=VALUE for `colmap-fusion --stereo-fusion`
  bool is_sac = false;           // the row "gap closed" and rank are computed for
  bool is_ceiling = false;       // the no-errors union: the upper bound, not ranked
  // Folder below OUT/rows: <block_id>/<slug of name>. Rows with equal folders are the same run.
  std::string Folder() const;
};

struct SkippedBlock {
  std::string scene;
  std::string reason;            // printed and recorded in bench.json
};

struct BenchPlan {
  std::vector<BlockSpec> blocks;   // each distinct simulation once, in first-use order
  std::vector<RowSpec> rows;       // table order: per scale, per block: methods, COLMAP, ceiling; then ablations
  std::vector<SkippedBlock> skipped;
};

// Throws ConfigError (naming the option) for unknown block or method names, an empty method list, or scales
// <= 0.
BenchPlan BuildBenchPlan(const QualityBenchOptions& options);

// Lower-case letters, digits and '_' (others become '_', runs collapsed): folder names from row labels.
std::string Slug(const std::string& text);

}  // namespace sacfuse::bench
