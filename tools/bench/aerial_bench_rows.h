#pragma once
// `sacfuse bench`, aerial-bench part 5: running one block. Child processes (quality_bench_row.h's steps, measured
// with wait4 as every bench row):
//  * the block: `PYTHON make_block.py ARGS --out OUT/aerial/<name> --force`, once (reused when meta.json exists);
//  * sacfuse: `sacfuse run` of a generated config (`input: {format: colmap, path: BLOCK}`, `output: {dir, format:
//    las}`, every other key default) in OUT/aerial/rows/<name>/sacfuse, then `score.py fused.las --block BLOCK
//    --json-only`; recorded in its row.json with a key (config, command, block arguments) and reused as the other
//    rows are (resume, --force);
//  * the peers: `peers.py --block BLOCK --methods tsdf,union,oracle[,colmap_best --grid ...]`, only for methods
//    BLOCK/peers.json lacks (or has failed); their rows are read from peers.json (colmap_best's also without
//    `colmap`, when peers.json has it from an earlier run).
// A failing step fails its rows (with the error) and the bench goes on.
#include <ostream>
#include <string>
#include <vector>

#include "tools/bench/aerial_bench_plan.h"
#include "tools/bench/aerial_bench_table.h"

namespace sacfuse::bench {

struct AerialContext {
  std::string sacfuse;     // the sacfuse binary
  std::string python;      // AerialPlan::python
  std::string bench_dir;   // AerialPlan::bench_dir
  std::string root;        // OUT/aerial
  bool colmap = false;     // add peers.py's colmap_best (COLMAP rows are on and colmap was found)
  bool force = false;
  bool keep_clouds = false;
};

// peers.py methods of a block: tsdf, union, oracle, and colmap_best when `colmap`.
std::vector<std::string> AerialPeerMethods(bool colmap);

// The block's rows in AerialMethods() order (sacfuse first); progress is printed to `out` row by row.
std::vector<AerialRow> RunAerialBlock(const AerialBlockSpec& block, const AerialContext& context, std::ostream& out);

}  // namespace sacfuse::bench
