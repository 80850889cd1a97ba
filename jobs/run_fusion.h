#pragma once
// `sacfuse run`: read the configured input, fuse, write DIR/fused.las (and the DSM, DIR/dsm.tif, when output.dsm
// asks for it: jobs/dsm_product.h), the effective config and run_report.json,
// score the cloud when evaluation.reference is set (DIR/eval.json, eval/eval_runner.h), then write the HTML report
// once (report/report_writer.h).
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "config/job_config.h"
#include "core/fusion_stats.h"
#include "core/sac_fusion.h"
#include "jobs/coregistered_block.h"
#include "jobs/dsm_product.h"
#include "jobs/ortho_product.h"
#include "jobs/output_lock.h"
#include "io/las_writer.h"
#include "io/stage_clock.h"

namespace sacfuse {

struct ViewRunStats {
  std::string name;
  uint64_t input_pixels = 0;   // valid depth pixels read
  uint64_t output_points = 0;  // points written with this view as source
};

struct RunSummary {
  std::string las_path;
  std::string effective_config_path;
  std::string report_path;
  std::string method;
  uint64_t input_points = 0;   // valid depth pixels over all views
  uint64_t output_points = 0;
  std::vector<ViewRunStats> views;
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;
  double peak_rss_mib = 0.0;
  FusionStats fusion;  // the method's (tiled: summed over the tiles this invocation computed)
  size_t superpixels_computed = 0;
  size_t tiles_run = 0;  // tiled SAC (tiling.tile_size_m > 0): tiles with views; 0 = untiled
  size_t tiles_computed = 0;  // tiled: computed by this invocation (the rest were verified done and skipped)
  size_t tiles_skipped = 0;
  std::vector<std::pair<std::string, std::string>> failed_tiles;  // tiled: id, reason; then no fused.las
  double tile_size_m = 0.0;        // as run (resolved when tiling.tile_size_m was 0 = automatic)
  std::string tiling_reason;       // why untiled / this tile size
  double memory_budget_gib = 0.0;  // resources.memory_gb
  double memory_estimate_gib = 0.0;  // untiled: the whole block; tiled: the largest tile
  int threads = 0;
  CoregistrationOutcome coregistration;  // the pose corrections before fusion (jobs/coregistered_block.h)
  double superpixel_seconds = 0.0;  // the superpixel (and colour cache) pass; untiled: all loading
  double tiles_seconds = 0.0;       // tiled: the tile stage
  double merge_seconds = 0.0;       // tiled: merging the tiles into fused.las
  double write_seconds = 0.0;       // untiled: wall time inside the LAS/LAZ writer during the fusion stage
  // Every stage of the job in the order it ran, with wall and CPU seconds (io/stage_clock.h): opening the input,
  // the tiling decision, co-registration, then untiled "load + superpixels", "fusion", "write fused cloud", or
  // tiled "tile plan", "superpixels", "tiles", "merge"; then "run report", "scoring" (evaluation.reference set) and
  // "HTML report". wall_seconds / cpu_seconds above end with the fused cloud; total_* include every stage.
  std::vector<StageTime> stages;
  double total_wall_seconds = 0.0;
  double total_cpu_seconds = 0.0;
  std::string eval_text;            // evaluation.reference set: the score table and F1 lines (eval/eval_runner.h)
  DsmOutcome dsm;                   // output.dsm: DIR/dsm.tif (jobs/dsm_product.h)
  OrthoOutcome ortho;               // output.ortho: DIR/ortho.tif (jobs/ortho_product.h)
};

// Called as work proceeds: stage name, units done, units total.
using RunProgress = std::function<void(const std::string& stage, size_t done, size_t total)>;

// Runs one job; the caller holds the output folder's writer lock (jobs/output_lock.h), which records the job's
// settings hash and inputs digest. Throws InputError/ConfigError/Error with context; never leaves a partial
// fused.las, and replaces fused.las, run_report.json, eval.json and the HTML report only when it has the new ones
// (a run with failed tiles writes none of them; a scoring error is thrown after the report is written without
// scores). Deletes the temporary files of gone processes first (jobs/output_lock.h). The views' files are pinned:
// one changed during the run fails it before the cloud is written (InputError naming the file); the other
// format's cloud of an earlier run is removed once the new one is written.
// Tiled runs resume (jobs/tiled_run.h): `rerun_tiles` names tiles to recompute even when done (ConfigError
// naming any id that is not a tile with views, or when the run is not tiled); a tile that fails is listed in
// failed_tiles and the job returns without merging.
RunSummary RunFusionJob(const JobConfig& config, OutputWriterLock& lock, const RunProgress& progress = {},
                        const std::vector<std::string>& rerun_tiles = {});

}  // namespace sacfuse
