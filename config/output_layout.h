#pragma once
// Where a job's outputs live, one function per file or folder under output.dir (every other file names them
// through these):
//   DIR/fused.laz | fused.las | fused.copc.laz   the fused cloud (output.format); a run removes the other
//                               formats' files of an earlier run once it has its own (jobs/output_lock.h)
//   DIR/tiles.vpc               tiled runs: the tile files as a virtual point cloud (io/vpc_writer.h)
//   DIR/sacfuse.lock            the one-writer lock of `run` and `merge` (jobs/output_lock.h)
//   DIR/sacfuse.workers.lock    the shared lock of `tile`, `plan` and `report` processes (jobs/output_lock.h)
//   DIR/sacfuse.effective.yaml  the config actually used
//   DIR/run_report.json         numbers of the run
//   DIR/eval.json               scores against evaluation.reference (eval/eval_runner.h)
//   DIR/sacfuse.log             the log
//   DIR/run_state.json          running | failed | succeeded, of the last `sacfuse run` (jobs/run_state.h)
//   DIR/plan.json               the tile plan shared by every worker (tiles/tile_plan.h)
//   DIR/coregistration.json     per-view pose corrections, reused while inputs and options are unchanged
//                               (jobs/coregistered_block.h)
//   DIR/tiles/                  per-tile state of tiled runs (tiles/tile_manifest.h, tiles/tile_marker.h)
//   DIR/dsm.tif                 the DSM (output.dsm), one Cloud Optimized GeoTIFF (jobs/dsm_product.h), or
//   DIR/dsm.vrt + DIR/dsm/      a VRT over COG blocks (output.raster_layout)
//   DIR/ortho.tif               the true orthophoto (output.ortho; jobs/ortho_product.h), or
//   DIR/ortho.vrt + DIR/ortho/  a VRT over COG blocks, as the DSM
//   DIR/report/                 the HTML report (report/report_writer.h)
//   DIR/superpixels/            superpixel and colour caches (or fusion.superpixel_cache_dir; jobs/superpixel_cache.h)
#include <string>

#include "config/job_config.h"

namespace sacfuse {

std::string FusedLasPath(const JobConfig& config);  // DIR/fused.laz, fused.las or fused.copc.laz (output.format)
// The fused cloud's path for any output.format value ("laz", "las" or "copc").
std::string FusedPathOfFormat(const JobConfig& config, const std::string& format);
std::string TileIndexPath(const JobConfig& config);    // DIR/tiles.vpc
std::string WriterLockPath(const JobConfig& config);   // DIR/sacfuse.lock
std::string WorkersLockPath(const JobConfig& config);  // DIR/sacfuse.workers.lock
std::string EffectiveConfigPath(const JobConfig& config);
std::string RunReportPath(const JobConfig& config);
std::string EvalJsonPath(const JobConfig& config);
std::string LogPath(const JobConfig& config);
std::string RunStatePath(const JobConfig& config);
std::string PlanJsonPath(const JobConfig& config);
std::string CoregistrationPath(const JobConfig& config);
std::string TilesDir(const JobConfig& config);
std::string ReportDir(const JobConfig& config);  // the default report folder (`sacfuse report --out` may differ)
std::string DsmPath(const JobConfig& config);       // DIR/dsm.tif
std::string DsmVrtPath(const JobConfig& config);    // DIR/dsm.vrt
std::string DsmBlocksDir(const JobConfig& config);  // DIR/dsm
std::string OrthoPath(const JobConfig& config);       // DIR/ortho.tif
std::string OrthoVrtPath(const JobConfig& config);    // DIR/ortho.vrt
std::string OrthoBlocksDir(const JobConfig& config);  // DIR/ortho

// The superpixel (and colour) cache folder of a job: fusion.superpixel_cache_dir, or <output.dir>/superpixels.
std::string SuperpixelCacheDir(const JobConfig& config);
// Cache file of an image name ("nadir/0001.jpg" -> "<dir>/nadir/0001.jpg.spx").
std::string SuperpixelCachePath(const std::string& cache_dir, const std::string& image_name);
// Colour cache file of an image name ("nadir/0001.jpg" -> "<dir>/nadir/0001.jpg.rgb"): the image resampled to
// the depth raster (io/colour_raster_io.h), written by the superpixel pass so tiles read colour windows.
std::string ColourCachePath(const std::string& cache_dir, const std::string& image_name);

}  // namespace sacfuse
