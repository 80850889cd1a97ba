#pragma once
// Where a job's outputs live, one function per file or folder under output.dir (every other file names them
// through these):
//   DIR/fused.laz | fused.las   the fused cloud (output.format)
//   DIR/sacfuse.effective.yaml  the config actually used
//   DIR/run_report.json         numbers of the run
//   DIR/sacfuse.log             the log
//   DIR/run_state.json          running | failed | succeeded, of the last `sacfuse run` (jobs/run_state.h)
//   DIR/tiles/                  per-tile state of tiled runs (jobs/tiled_run.h)
//   DIR/superpixels/            superpixel and colour caches (or fusion.superpixel_cache_dir; jobs/superpixel_cache.h)
#include <string>

#include "config/job_config.h"

namespace sacfuse {

std::string FusedLasPath(const JobConfig& config);  // DIR/fused.<output.format>
std::string EffectiveConfigPath(const JobConfig& config);
std::string RunReportPath(const JobConfig& config);
std::string LogPath(const JobConfig& config);
std::string RunStatePath(const JobConfig& config);
std::string TilesDir(const JobConfig& config);

}  // namespace sacfuse
