#pragma once
// `sacfuse bench`, aerial-bench part 1: which blocks of the independent aerial-bench (../shared/aerial-bench, a
// simulator over real LiDAR with its own peers and scorer) to make and how. The six definitions are those of
// issue 12 and docs/evaluation.md: Montpellier = the six IGN tiles at GSD 0.25 m, Zurich = zurich.las at GSD 0.125 m
// with 0.25 m DSM cells, St Barth (the third city) = IGN's 100 m Saint-Barthelemy subset as Zurich, `_e25` =
// every error x 2.5. Pure but for existence checks of the files it needs.
#include <string>
#include <vector>

#include "tools/bench/quality_bench_plan.h"

namespace sacfuse::bench {

struct AerialBlockSpec {
  std::string name;                    // montpellier, montpellier_e25, zurich, zurich_e25, stbarth, stbarth_e25
  std::vector<std::string> make_args;  // make_block.py's arguments before --out (LiDAR files expanded)
  // LiDAR files of make_args that are LAZ: make_block.py reads uncompressed LAS only, so each is decoded with
  // sacfuse's reader (io/las_copy.h) into OUT/aerial/lidar/<stem>.las, which replaces it on the command line.
  std::vector<std::string> laz_inputs;
};

struct AerialPlan {
  std::string bench_dir;               // the aerial-bench folder (make_block.py, score.py, peers.py)
  std::string python;                  // interpreter of its scripts
  std::vector<AerialBlockSpec> blocks;
  std::vector<SkippedBlock> skipped;   // scene "aerial <name>"
};

// Every name --aerial-blocks accepts.
std::vector<std::string> AerialBlockNames();

// $SACFUSE_SHARED/aerial-bench, else ../shared/aerial-bench next to the source tree; "" when neither exists.
std::string DefaultAerialBenchDir();

// The blocks of options.aerial_blocks. A block is skipped (with the reason) when the aerial-bench folder has no
// make_block.py, the interpreter is missing or the block's LiDAR files are not in options.lidar_dir. Throws
// ConfigError naming --aerial-blocks for an unknown name.
AerialPlan BuildAerialPlan(const QualityBenchOptions& options);

}  // namespace sacfuse::bench
